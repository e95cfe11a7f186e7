"""A short tour of rotorflow from Python, in the order of a notebook's cells.

    python3 python/examples/tour.py
"""

import numpy as np

import rotorflow as rf

# --- The algebra ---------------------------------------------------------------------------
# ANCHOR: algebra
# Cl(3): blades are attributes, `*` is the geometric product, `^` the outer product, `|` the
# inner product, `~` the reverse.
alg = rf.Algebra(3)
e1, e2, e3 = alg.e1, alg.e2, alg.e3
print("e1 e2 =", e1 * e2, "  e1 ^ e2 =", e1 ^ e2, "  (e1 + e2) | e1 =", (e1 + e2) | e1)

# A rotor R = exp(-theta B / 2) turns by theta in the plane B, from its first vector toward
# its second: a quarter turn in e12 takes e1 to e2.
r = (alg.e12 * (-np.pi / 4)).exp()
print("R e1 R~ =", r.sandwich(e1))
assert abs(r.sandwich(e1)["e2"] - 1.0) < 1e-15

# The exponential is a closed form in every dimension, also for bivectors that are not simple
# (two planes at once in 4D), and log inverts it.
a4 = rf.Algebra(4)
b = a4.bivector([0.5, 0.0, 0.0, 0.0, 0.0, 1.2])  # 0.5 e12 + 1.2 e34
print("exp(0.5 e12 + 1.2 e34) =", b.exp())
assert np.abs((b.exp().log() - b).coefficients).max() < 1e-15

# Other signatures: projective, conformal and spacetime algebras.
print("PGA:", rf.Algebra.pga(3), " CGA:", rf.Algebra.cga(3), " STA:", rf.Algebra.spacetime())
# ANCHOR_END: algebra

# --- Batches: arrays of shape (M, 2^N) ------------------------------------------------------
# ANCHOR: batches
rng = np.random.default_rng(1)
thetas = np.zeros((1000, 16))
thetas[:, [3, 5, 6, 9, 10, 12]] = rng.normal(size=(1000, 6))  # the six bivector blades
rotors = a4.exp(thetas)
unit = a4.product(rotors, a4.reverse(rotors))
print("max |R R~ - 1| over 1000 4D rotors:", np.abs(unit - np.eye(16)[0]).max())
# ANCHOR_END: batches

# --- Fixed-size rotors with scipy's verbs ----------------------------------------------------
# ANCHOR: rotors
q = rf.Rotor3.from_rotvec(rng.normal(size=(5, 3)))
points = rng.normal(size=(5, 3))
print("rotated points:\n", q.apply(points))
print("quaternions (x, y, z, w):\n", q.as_quat())
half = rf.Rotor3.identity().slerp(q[0], 0.5)
assert np.allclose((half * half).as_matrix(), q[0].as_matrix())

r4 = rf.Rotor4.from_bivector([0.3, 0.0, 0.0, 0.0, 0.0, 0.7])
print("4D rotation matrix:\n", r4.as_matrix().round(3))
# ANCHOR_END: rotors

# --- Bodies and motion -------------------------------------------------------------------
# ANCHOR: bodies
tesseract = rf.Body("tesseract:1,1.2,1.5,2")
print("plane moments of the tesseract:", tesseract.plane_moments())
run = rf.simulate(tesseract, omega=[1, 0.05, 0.02, 0.03, 0.04, 0.7], t_end=10, samples=11, integrator="yoshida4")
print("omega at t = 10:", run["omega"][-1].round(6), " energy drift:", run["drift"]["energy"])

# Two equal second moments: a closed form exists in any N.
closed = rf.exact(rf.Body.principal([1, 1, 1, 1.5]), omega=[0.3, 0.4, 0.2, 0.5, 0.1, 0.3], t_end=10, samples=11)
numeric = rf.simulate(rf.Body.principal([1, 1, 1, 1.5]), omega=[0.3, 0.4, 0.2, 0.5, 0.1, 0.3], t_end=10, samples=11, integrator="dop853", rtol=1e-12, atol=1e-14)
gap = np.abs(closed["omega"] - numeric["omega"]).max()
print("closed form against dop853:", gap)
assert gap < 1e-9
# ANCHOR_END: bodies

# --- Scenes: bodies that move as well as turn --------------------------------------------
# ANCHOR: scene
drop = rf.Scene.from_dict({
    "dim": 3, "gravity": [0, 0, -9.81], "t_end": 1.0, "dt": 0.01,
    "body": [{"name": "ball", "shape": "ball:3,0.5", "position": [0, 0, 2]}],
})
run = drop.run(samples=11)  # in a notebook, `run` shows the animation
data = run.data()  # the keys of `rotorflow scene --output`
z = data["bodies"][0]["position"][:, 2]
print("free fall, z(t):", z.round(4))
assert np.abs(z - (2.0 - 0.5 * 9.81 * data["times"] ** 2)).max() < 1e-12
# ANCHOR_END: scene
