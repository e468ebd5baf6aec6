// Wheel forging punch at its start position, in mm: a cylinder of radius
// 44.9 mm (0.1 mm clearance in the die bore) whose face at z = 40 touches the slug, with a 5 mm
// recess for the hub (r < 15) and one for the rim (r 40 .. 44.9). It moves 20 mm down.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 40, 0, 0, 50, 44.9};
Cylinder(2) = {0, 0, 39, 0, 0, 6, 15};      // hub recess, face at z = 45
Cylinder(3) = {0, 0, 39, 0, 0, 6, 44.9};    // rim recess: annulus r 40 .. 44.9, face at z = 45
Cylinder(4) = {0, 0, 38, 0, 0, 8, 40};
BooleanDifference(5) = { Volume{3}; Delete; }{ Volume{4}; Delete; };
BooleanDifference(6) = { Volume{1}; Delete; }{ Volume{2, 5}; Delete; };
