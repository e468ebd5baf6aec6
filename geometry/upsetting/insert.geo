// A 7.5 mm cube beside the billet (x from 12 to 19.5 mm, on the symmetry planes y = 0 and z = 0): a second
// body for scene_combined.yaml, pushed against the billet's side. Hexahedra of spacing h.
DefineConstant[ h = {1.25, Name "spacing (mm)"} ];
n = Round(7.5 / h);
If (n < 1)
  n = 1;
EndIf
Point(1) = {12, 0, 0};
Point(2) = {19.5, 0, 0};
Point(3) = {19.5, 7.5, 0};
Point(4) = {12, 7.5, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1};
Recombine Surface{1};
Extrude {0, 0, 7.5} { Surface{1}; Layers{n}; Recombine; }
