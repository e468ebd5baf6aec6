// The standard 6:3:2 friction ring (outside diameter 30 mm, inside 15 mm, height 10 mm), one eighth:
// a quarter annulus in x, y >= 0 and the upper half z = 0..5, in mm. Structured hexahedra at spacing
// h (rkprep sets it), so the particles lie on every face.
DefineConstant[ h = {1.25, Name "spacing (mm)"} ];
Ri = 7.5;
Ro = 15;
H = 5;
nr = Round((Ro - Ri) / h);
na = Round(Pi * (Ri + Ro) / 4 / h);
nz = Round(H / h);
Point(1) = {0, 0, 0};
Point(2) = {Ri, 0, 0};
Point(3) = {Ro, 0, 0};
Point(4) = {0, Ro, 0};
Point(5) = {0, Ri, 0};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = na + 1;
Transfinite Surface{1};
Recombine Surface{1};
v[] = Extrude {0, 0, H} { Surface{1}; Layers{nz}; Recombine; };
