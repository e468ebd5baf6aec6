// Rigid floor: a plate whose top face is z = 0, in mm.
SetFactory("OpenCASCADE");
Box(1) = {-20, -20, -3, 60, 50, 3};
