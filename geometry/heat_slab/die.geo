// A flat plate under the bar: its top face z = 0 is the bar's lower face, in mm.
SetFactory("OpenCASCADE");
Box(1) = {-2, -2, -3, 24, 8, 3};
