"""(a) cablefem's wave kinematics against the closed forms, above and below the mean level, for
each stretching, in shallow, intermediate and deep water; (b) the compiled face against the numpy
face and the exact gradients against central differences."""

import numpy as np

from cablefem.waves import Sea
from cablefem.waves.compiled import water_at, water_of
from verification.waves.closed_forms import sea_at

GRAVITY = 9.81
#: (name, depth [m], components (A [m], omega [rad/s], beta [rad], phi [rad]))
CASES = (("regular, shallow (kh 0.3)", 10.0, ((0.5, 0.3 * np.sqrt(GRAVITY * 0.03 * np.tanh(0.3)), 0.0, 0.0),)),
         ("regular, intermediate", 60.0, ((3.0, 2 * np.pi / 10.0, 0.4, 1.0),)),
         ("regular, deep (kh 40)", 200.0, ((1.0, np.sqrt(GRAVITY * 0.2 * np.tanh(40.0)), -0.7, 2.0),)),
         ("three components", 80.0, ((2.0, 0.55, 0.0, 0.3), (1.0, 0.9, 0.5, 2.2), (0.6, 1.4, -1.0, 4.0))))


def points_in(depth, eta_scale, rng, count=24):
    """Points from the seabed to just below the crest and above the mean level: (count, 3) [m]."""
    x = rng.uniform(-300.0, 300.0, count)
    y = rng.uniform(-100.0, 100.0, count)
    z = np.concatenate((rng.uniform(-depth, 0.0, count - count // 3), rng.uniform(0.0, eta_scale, count // 3)))
    return np.column_stack((x, y, z))


def against_closed_forms(rng, times=(0.0, 3.7, 11.2)):
    """Largest error of eta, u and a relative to A, A omega, A omega^2 of the largest component, per case
    and stretching, at wet points (z <= eta)."""
    rows = []
    for name, depth, components in CASES:
        A = np.array([c[0] for c in components])
        omega = np.array([c[1] for c in components])
        scale = (A.max(), (A * omega).max(), (A * omega ** 2).max())
        for stretching in ("wheeler", "vertical", "none"):
            sea = Sea.from_components(A, omega, [c[2] for c in components], [c[3] for c in components], depth,
                                      GRAVITY, stretching=stretching)
            worst = np.zeros(3)
            wet = above = 0
            for t in times:
                points = points_in(depth, A.sum(), rng)
                K = sea.kinematics(points, t)
                for i, point in enumerate(points):
                    eta, u, a = sea_at(components, depth, GRAVITY, stretching, point, t)
                    if point[2] > eta:
                        continue
                    wet += 1
                    above += point[2] > 0.0
                    errors = (abs(K.eta[i] - eta), np.abs(K.velocity[i] - u).max(), np.abs(K.acceleration[i] - a).max())
                    worst = np.maximum(worst, np.array(errors) / scale)
            rows.append({"case": name, "stretching": stretching, "points": wet, "above_mean_level": int(above),
                         "eta": worst[0], "velocity": worst[1], "acceleration": worst[2]})
    return rows


def faces_and_gradients(rng):
    """Largest difference compiled - numpy (absolute) and exact gradient - central difference (relative
    to the gradient's scale k A omega, k A omega^2) over the cases, stretchings and a ramp."""
    compiled = gradient = 0.0
    u, a, du, da = np.zeros(3), np.zeros(3), np.zeros((3, 3)), np.zeros((3, 3))
    for _, depth, components in CASES:
        A, omega = np.array([c[0] for c in components]), np.array([c[1] for c in components])
        for stretching in ("wheeler", "vertical", "none"):
            sea = Sea.from_components(A, omega, [c[2] for c in components], [c[3] for c in components], depth,
                                      GRAVITY, stretching=stretching, ramp=20.0)
            k = sea.arrays[2]
            scale = ((k * A * omega).max(), (k * A * omega ** 2).max())
            # below the troughs and above the seabed: the stretched height is smooth there
            points = np.column_stack((rng.uniform(-300.0, 300.0, (24, 2)),
                                      rng.uniform(-0.95 * depth, -1.05 * A.sum(), 24)))
            t = 7.3
            K = sea.kinematics(points, t, gradients=True)
            water = water_of(sea)
            for i, point in enumerate(points):
                eta, wet = water_at(water, point, t, u, a, du, da, True)
                compiled = max(compiled, abs(eta - K.eta[i]), np.abs(u - K.velocity[i]).max(),
                               np.abs(a - K.acceleration[i]).max(), np.abs(du - K.velocity_gradient[i]).max(),
                               np.abs(da - K.acceleration_gradient[i]).max())
            step = 1e-4 * depth
            for j in range(3):
                shift = np.zeros(3)
                shift[j] = step
                plus, minus = sea.kinematics(points + shift, t), sea.kinematics(points - shift, t)
                for field, exact, s in (("velocity", K.velocity_gradient, scale[0]),
                                        ("acceleration", K.acceleration_gradient, scale[1])):
                    central = (getattr(plus, field) - getattr(minus, field)) / (2.0 * step)
                    gradient = max(gradient, np.abs(central - exact[:, :, j]).max() / s)
    return {"compiled_vs_numpy": compiled, "gradient_vs_central_difference": gradient}
