// Patch-test cube, 10 x 10 x 10 mm of structured hexahedra in the octant x, y, z >= 0, in mm.
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.25, Name "spacing (mm)"} ];
Box(1) = {0, 0, 0, 10, 10, 10};
Transfinite Curve{:} = Round(10 / h) + 1;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
