// Upsetting billet: aluminium cylinder D0 = H0 = 20 mm, in mm. One eighth is
// modeled: symmetry planes x = 0, y = 0 (quarter) and z = 0 (mid-height); the top die presses at
// z = 10. Structured hexahedra (O-grid) so the particles (mesh nodes) lie on every surface.
// rkprep sets h, the particle spacing in mm.
DefineConstant[ h = {1.25, Name "spacing (mm)"} ];
R = 10;
H = 10;
n = Round(Pi * R / (4 * h));
If (n < 1)
  n = 1;
EndIf
nz = Round(H / h);
If (nz < 1)
  nz = 1;
EndIf
c = 0.5 * R;
Point(1) = {0, 0, 0};
Point(2) = {c, 0, 0};
Point(3) = {c, c, 0};
Point(4) = {0, c, 0};
Point(5) = {R, 0, 0};
Point(6) = {R / Sqrt(2), R / Sqrt(2), 0};
Point(7) = {0, R, 0};
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
Transfinite Curve{5, 7, 9} = n + 1;
Transfinite Surface{1, 2, 3};
Recombine Surface{1, 2, 3};
Extrude {0, 0, H} { Surface{1, 2, 3}; Layers{nz}; Recombine; }
