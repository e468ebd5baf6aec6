// 10 x 10 x 5 mm block of structured hexahedra resting on z = 0, in mm; h = spacing (mm).
SetFactory("OpenCASCADE");
DefineConstant[ h = {1.25, Name "spacing (mm)"} ];
Box(1) = {0, 0, 0, 10, 10, 5};
Transfinite Curve{:} = Round(10 / h) + 1;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
