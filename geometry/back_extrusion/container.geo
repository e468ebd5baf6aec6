// Rigid container: a cup with inner diameter 40.2 mm (0.1 mm radial clearance) and floor at z = 0, in mm (a closed solid whose
// inner surface faces the billet).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -5, 0, 0, 55, 27};
Cylinder(2) = {0, 0, 0, 0, 0, 56, 20.1};  // 0.1 mm clearance: the faceted bore must not cut the billet
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
