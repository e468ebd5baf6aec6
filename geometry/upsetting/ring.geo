// A ring die at rest around the billet's mid-height (inner radius 12 mm, outer 15 mm, from z = -1 to
// 3 mm, 2.9 mm below the top die's lowest position in scene_closed_die.yaml): it stops the bulge, so the
// second stage's flow is closed-die upsetting.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -1, 0, 0, 4, 15};
Cylinder(2) = {0, 0, -1, 0, 0, 4, 12};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
