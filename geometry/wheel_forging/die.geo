// Wheel forging lower die, a closed solid of revolution about z, in mm. The
// cavity it forms with the punch at full stroke (punch.geo lowered 20 mm):
//   hub        r <  15 mm   z   0 .. 25
//   inner web  r 15 .. 31   z   0 .. 20   (the slug, r < 30, stands on the floor z = 0)
//   thin web   r 31 .. 40   z  12 .. 20   (the floor steps up 1 mm outside the slug)
//   rim        r 40 .. 45   z  -5 .. 25   (a groove in the die floor, a recess in the punch)
// Volume at full stroke: pi (15^2 25 + (31^2 - 15^2) 20 + (40^2 - 31^2) 8 + (45^2 - 40^2) 30)
// = 119 580 mm^3 = 1.057 x the slug's 113 097 mm^3 (about 5 % larger).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -15, 0, 0, 85, 55};   // die block, z -15 .. 70
Cylinder(2) = {0, 0, 0, 0, 0, 80, 31};     // floor under the slug and hub
Cylinder(3) = {0, 0, 12, 0, 0, 70, 45};    // thin web floor and the bore the punch slides in
Cylinder(4) = {0, 0, -5, 0, 0, 85, 45};    // rim groove: annulus r 40 .. 45
Cylinder(5) = {0, 0, -6, 0, 0, 87, 40};
BooleanDifference(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };
BooleanUnion(7) = { Volume{2}; Delete; }{ Volume{3, 6}; Delete; };
BooleanDifference(8) = { Volume{1}; Delete; }{ Volume{7}; Delete; };
