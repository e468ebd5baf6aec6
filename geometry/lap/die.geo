// A flat die over the C-shaped block's top (z = 6 mm), in mm.
SetFactory("OpenCASCADE");
Box(1) = {-2, -2, 6, 14, 8, 2};
