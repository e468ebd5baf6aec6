// Taylor bar (section 5.1 of Wang et al. 2007), the whole copper cylinder: radius 3.2 mm, length 32.4 mm, in mm, axis +z,
// impact face z = 0. The quarter's O-grid (taylor_bar.geo) turned four times, so the full and the
// quarter model have the same particles in the quarter (the symmetry check).
DefineConstant[ h = {0.9, Name "spacing (mm)"} ];
R = 3.2;
L = 32.4;
n = Round(Pi * R / (4 * h));
If (n < 1)
  n = 1;
EndIf
nz = Round(L / h);
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
For k In {1:3}
  Rotate {{0, 0, 1}, {0, 0, 0}, k * Pi / 2} { Duplicata { Surface{1, 2, 3}; } }
EndFor
Coherence;
Transfinite Curve{:} = n + 1;
Transfinite Surface{:};
Recombine Surface{:};
Extrude {0, 0, L} { Surface{:}; Layers{nz}; Recombine; }
