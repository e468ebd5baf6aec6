// Rigid punch: diameter 28 mm with a 1 mm edge radius, face at z = 30 mm (the billet top), in mm.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 30, 0, 0, 30, 14};
f() = Abs(Boundary{ Volume{1}; });
e() = Unique(Abs(Boundary{ Surface{f()}; }));
bottom[] = Curve In BoundingBox{-15, -15, 29.9, 15, 15, 30.1};
Fillet{1}{bottom[]}{1}
