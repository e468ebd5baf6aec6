// A bar for one-dimensional heat conduction along x: length 20 mm, square section 4 mm, in mm.
// Structured hexahedra at spacing h (rkprep sets it), so the particles lie on every face.
DefineConstant[ h = {1.0, Name "spacing (mm)"} ];
L = 20;
W = 4;
nx = Round(L / h);
nw = Round(W / h);
If (nw < 1)
  nw = 1;
EndIf
Point(1) = {0, 0, 0};
l[] = Extrude {L, 0, 0} { Point{1}; Layers{nx}; };
s[] = Extrude {0, W, 0} { Line{l[1]}; Layers{nw}; Recombine; };
v[] = Extrude {0, 0, W} { Surface{s[1]}; Layers{nw}; Recombine; };
