// Two elastic bars in impact: the target, at rest, z = 0 to 50 mm. A quarter of an aluminium cylinder, radius 5 mm,
// length 50 mm, in mm; symmetry planes x = 0 and y = 0, axis +z. Structured hexahedra (an O-grid:
// a square core and two curved blocks) so that the particles (mesh nodes) lie on every surface.
// rkprep sets h, the particle spacing in mm.
DefineConstant[ h = {1.0, Name "spacing (mm)"} ];
R = 5;
L = 50;
z0 = 0;
n = Round(Pi * R / (4 * h));   // divisions of each core edge and of each quarter-arc half
If (n < 1)
  n = 1;
EndIf
m = n;                         // radial divisions from the core to the rim
nz = Round(L / h);             // layers along the axis
c = 0.5 * R;                   // core square side

Point(1) = {0, 0, z0};
Point(2) = {c, 0, z0};
Point(3) = {c, c, z0};
Point(4) = {0, c, z0};
Point(5) = {R, 0, z0};
Point(6) = {R / Sqrt(2), R / Sqrt(2), z0};
Point(7) = {0, R, z0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {2, 5};
Circle(6) = {5, 1, 6};
Line(7) = {6, 3};
Circle(8) = {6, 1, 7};
Line(9) = {7, 4};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, -2};
Curve Loop(3) = {-7, 8, 9, -3};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Plane Surface(3) = {3};
Transfinite Curve{1, 2, 3, 4, 6, 8} = n + 1;
Transfinite Curve{5, 7, 9} = m + 1;
Transfinite Surface{1, 2, 3};
Recombine Surface{1, 2, 3};
Extrude {0, 0, L} { Surface{1, 2, 3}; Layers{nz}; Recombine; }
