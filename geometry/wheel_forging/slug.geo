// Wheel forging slug: aluminium cylinder D = 60 mm, H = 40 mm, in mm. A 30-degree
// sector between the half-planes at 30 and 60 degrees about the z axis is modeled, with symmetry
// planes of non-axis-aligned normal on its cut faces. Structured hexahedra (a kite at the axis and two
// blocks out to the rim) so the particles (mesh nodes) lie on every surface. rkprep sets h (mm).
DefineConstant[ h = {2.5, Name "spacing (mm)"} ];
R = 30;
H = 40;
t1 = Pi / 6;  // the sector's first cut face ...
t2 = Pi / 3;  // ... and its second
tm = 0.5 * (t1 + t2);
ni = Round(R * (t2 - t1) / 2 / h);  // cells along each half of the rim arc
If (ni < 1)
  ni = 1;
EndIf
c = ni * h;  // the kite's side along the cut faces
If (c > 0.4 * R)
  c = 0.4 * R;
EndIf
nr = Round((R - c) / h);
If (nr < 1)
  nr = 1;
EndIf
nz = Round(H / h);
If (nz < 1)
  nz = 1;
EndIf
cm = c / Cos(0.5 * (t2 - t1));
Point(1) = {0, 0, 0};
Point(2) = {c * Cos(t1), c * Sin(t1), 0};
Point(3) = {cm * Cos(tm), cm * Sin(tm), 0};
Point(4) = {c * Cos(t2), c * Sin(t2), 0};
Point(5) = {R * Cos(t1), R * Sin(t1), 0};
Point(6) = {R * Cos(tm), R * Sin(tm), 0};
Point(7) = {R * Cos(t2), R * Sin(t2), 0};
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
Transfinite Curve{1, 2, 3, 4, 6, 8} = ni + 1;
Transfinite Curve{5, 7, 9} = nr + 1;
Transfinite Surface{1, 2, 3};
Recombine Surface{1, 2, 3};
Extrude {0, 0, H} { Surface{1, 2, 3}; Layers{nz}; Recombine; }
