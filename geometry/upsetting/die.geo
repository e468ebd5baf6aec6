// Flat rigid upsetting die: a plate whose lower face touches the billet top (z = 10 mm), in mm.
SetFactory("OpenCASCADE");
Box(1) = {-2, -2, 10, 20, 20, 3};
