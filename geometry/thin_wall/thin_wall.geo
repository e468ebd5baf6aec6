// A thin copper wall standing on its edge (the stability study: 2 particles across a thin
// feature): thickness T = 1.2 mm along x, 12 mm wide (y) and 12 mm tall (z), in mm. Structured
// hexahedra; rkprep sets h, the particle spacing in mm; h = T gives one cell, 2 particles, across.
DefineConstant[ h = {1.2, Name "spacing (mm)"} ];
T = 1.2;
W = 12;
H = 12;
nx = Round(T / h);
If (nx < 1)
  nx = 1;
EndIf
ny = Round(W / h);
nz = Round(H / h);
Point(1) = {0, 0, 0};
Point(2) = {T, 0, 0};
Point(3) = {T, W, 0};
Point(4) = {0, W, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};
Extrude {0, 0, H} { Surface{1}; Layers{nz}; Recombine; }
