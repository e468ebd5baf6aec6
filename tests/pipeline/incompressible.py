"""A nearly incompressible material (nu = 0.499) keeps a smooth pressure field: the Taylor bar at
1.2 mm spacing (532 particles, 2 ranks) to 10 us, the pressure's point-to-point oscillation
(scripts/pressure_oscillation.py: RMS of each particle's pressure less its neighbours' mean) against
the same bar at nu = 0.35, both with the default bulk viscosity (the Taylor scene turns it off).
Measured 2026-12-02: 0.093 GPa at nu = 0.499 against 0.054 GPa at nu = 0.35 (1.72x); pressure RMS
0.260 against 0.231 GPa. Without bulk viscosity nu = 0.499 rings: 3.53 GPa (its bulk waves carry
pressures rho c_L v of 95 GPa here); F-bar alone holds the volume but does not damp them."""
import shutil

import rkcase
from pressure_oscillation import check

tools = rkcase.tools_from_argv()
prep = tools.case("incompressible_prep")
tools.prep(prep, 2, sets=["discretization.spacing=1.2e-3"])
base = ["time.end=10e-6", "time.output_interval=10e-6"]
viscosity = ["bulk_viscosity.quadratic=1.5", "bulk_viscosity.linear=0.06"]
no_viscosity = ["bulk_viscosity.quadratic=0", "bulk_viscosity.linear=0"]


def oscillation(name, sets):
    case = tools.case(name)
    shutil.copytree(prep, case)
    tools.solve(case, 2, sets=base + sets)
    tools.post(case)
    return check(case)


ref = oscillation("incompressible_nu035", ["material.poisson_ratio=0.35"] + viscosity)
nearly = oscillation("incompressible_nu0499", ["material.poisson_ratio=0.499"] + viscosity)
ringing = oscillation("incompressible_nu0499_no_viscosity", ["material.poisson_ratio=0.499"] + no_viscosity)
ratio = nearly["oscillation_rms_gpa"] / ref["oscillation_rms_gpa"]
# 1.72x measured; 2.5x leaves for the spread between resolutions and ranks, and is far below the
# 65x of the ringing field
rkcase.check(ratio < 2.5, f"nu = 0.499: oscillation {nearly['oscillation_rms_gpa']:.3f} GPa RMS, {ratio:.2f}x that of "
             f"nu = 0.35 ({ref['oscillation_rms_gpa']:.3f} GPa)")
# the pressure itself: +12.5 % measured (the flow, not the compressibility, sets it)
rkcase.check(abs(nearly["pressure_rms_gpa"] / ref["pressure_rms_gpa"] - 1) < 0.25,
             f"pressure RMS {nearly['pressure_rms_gpa']:.3f} GPa against {ref['pressure_rms_gpa']:.3f} GPa at nu = 0.35")
# the check can fail: without the bulk viscosity the same field rings (65x measured)
rkcase.check(ringing["oscillation_rms_gpa"] > 10 * ref["oscillation_rms_gpa"],
             f"without bulk viscosity nu = 0.499 rings: {ringing['oscillation_rms_gpa']:.2f} GPa RMS")
