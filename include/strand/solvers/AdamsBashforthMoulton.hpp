// The 4th-order Adams-Bashforth-Moulton predictor-corrector for y' = f(t, y), registered with PETSc
// as the TS type "strand_abm4" (explicit; the TS's RHSFunction). Seed 001 (section 3) compares it
// with RK4 on the hub-beam; it costs two evaluations of f per step against RK4's four.
//
// PECE form with a fixed step h (Hairer, Norsett & Wanner, Solving ODEs I, Sec. III.1):
//   P  y* = y_n + h/24 (55 f_n - 59 f_{n-1} + 37 f_{n-2} - 9 f_{n-3})    (Adams-Bashforth, 4 steps)
//   E  f* = f(t_{n+1}, y*)
//   C  y_{n+1} = y_n + h/24 (9 f* + 19 f_n - 5 f_{n-1} + f_{n-2})        (Adams-Moulton, 3 steps)
//   E  f_{n+1} = f(t_{n+1}, y_{n+1})
// The first three steps, and the first after a change of h (the last step, cut to land on the
// final time), are classical RK4 steps, so the start keeps order 4.
// Stability (largest root of the PECE recurrence for y' = lambda y, computed; docs/validation.md):
//  - negative real axis (damped modes): stable for h |lambda| <= 1.28 (RK4: 2.79);
//  - imaginary axis (undamped oscillations): weakly UNSTABLE at every h omega > 0, the largest
//    root being 1 + 0.16 (h omega)^6 to leading order (1 + 1.6e-7 at h omega = 0.1, 1 + 1.0e-4 at
//    0.3, 1 + 1.5e-3 at 0.5, 1.12 at 1). Over N steps an undamped mode grows by
//    exp(0.16 (h omega)^6 N), so round-off in the highest mode of a stiff undamped model surfaces
//    after about 35 / (0.16 (h omega_max)^6) steps (measured: the 8-element flexible pendulum,
//    omega_max = 8.6e3 rad/s, blows up at t = 0.95 s with h = 6e-5 s). RK4 instead damps them,
//    |R(i h omega)| = 1 - (h omega)^6 / 144, up to h omega = 2 sqrt(2).
// Use it where seed 001 does: few, well-resolved modes, or damped models.
#pragma once
#include <petscts.h>

namespace strand::solvers {

inline constexpr const char* kTsAdamsBashforthMoulton = "strand_abm4";

// Registers the TS type (idempotent; call after PetscInitialize).
PetscErrorCode AdamsBashforthMoultonRegister();
// The history f_n, f_{n-1}, ... (count valid entries, taken with step h) at the current TS time, for
// checkpoints (borrowed; valid until the next step), and a history to continue from (copied; used by
// the next step if its h matches, so a restarted run continues the trajectory exactly).
PetscErrorCode AdamsBashforthMoultonGetHistory(TS ts, PetscInt* count, PetscReal* h, Vec f[4]);
PetscErrorCode AdamsBashforthMoultonSetHistory(TS ts, PetscInt count, PetscReal h, const Vec f[]);

}  // namespace strand::solvers
