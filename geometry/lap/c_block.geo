// A C-shaped block, in mm: 10 x 4 x 6 with a slot 2 mm high from x = 3 to its end (z = 2 to 4), so
// that a die pressing its top closes the slot: the arms' inner faces meet, a lap.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 10, 4, 6};
Box(2) = {3, -1, 2, 8, 6, 2};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
