// A slender beam, 10 x 10 mm in section (y, z) and 200 mm long (x), in mm, structured hexahedra:
// rkprep sets h, the particle spacing in mm (2.5 mm: 5 particles through the thickness).
DefineConstant[ h = {2.5, Name "spacing (mm)"} ];
B = 10;
L = 200;
nb = Round(B / h);
If (nb < 1)
  nb = 1;
EndIf
nl = Round(L / h);
Point(1) = {0, 0, 0};
Point(2) = {0, B, 0};
Point(3) = {0, B, B};
Point(4) = {0, 0, B};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = nb + 1;
Transfinite Surface{1};
Recombine Surface{1};
Extrude {L, 0, 0} { Surface{1}; Layers{nl}; Recombine; }
