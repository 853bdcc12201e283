#!/usr/bin/env python3
"""Closed-form rows of a `rolling` statement whose plane normal is `F.x` or
`F.y` of a fixed, tilted frame `F`, for codegen/tests/suite/rolling_planes.rs (see
tests/reference/README_rolling_planes.md).

A disc (radius r = 0.3, torus tire rt = 0.05) centred at G = (x, y, z),
turning with B = N.rotate_z(psi).rotate_x(theta).rotate_y(phi) about its
axle a = B.y, on the plane through Q = (0.2, 0, 0.1) with normal n = F.x
(F = N.rotate_y(0.3)) or n = F.y (F = N.rotate_x(0.4)). DESIGN's rows,
evaluated with numpy from rotation matrices (no dalembert code):
contact = (G - Q).n - r |n - (n.a) a| - rt; no slip = the velocity
v_G + w x (C - G) of the wheel's point at C = G - r u - rt n,
u = (n - (n.a) a) / |n - (n.a) a|, along F's next two axes in cyclic order
(F.y, F.z for F.x; F.z, F.x for F.y), as coefficients of the speeds.

usage: python scripts/rolling_planes_reference.py   # writes tests/reference/rolling_planes.json
"""
import json
import os

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def Rx(a): c,s=np.cos(a),np.sin(a); return np.array([[1,0,0],[0,c,-s],[0,s,c]])
def Ry(a): c,s=np.cos(a),np.sin(a); return np.array([[c,0,s],[0,1,0],[-s,0,c]])
def Rz(a): c,s=np.cos(a),np.sin(a); return np.array([[c,-s,0],[s,c,0],[0,0,1]])
r, rt = 0.3, 0.05
Q = np.array([0.2, 0.0, 0.1])
cases = {"F.x": (Ry(0.3), 0), "F.y": (Rx(0.4), 1)}
rng = np.random.default_rng(5)
out = {}
for key, (RF, k) in cases.items():
    states = []
    for _ in range(3):
        q = rng.uniform(-0.8, 0.8, 6); qd = rng.uniform(-1, 1, 6)
        x, y, z, psi, th, ph = q
        RA = Rz(psi); RC = RA @ Rx(th); RB = RC @ Ry(ph)
        G = np.array([x, y, z])
        n = RF[:, k]; a = RB[:, 1]
        e = n - n.dot(a) * a; L = np.linalg.norm(e)
        arm = -r * e / L - rt * n
        contact = (G - Q).dot(n) - r * L - rt
        def slip(qd):
            vG = qd[:3]
            w = qd[3] * np.array([0, 0, 1.0]) + qd[4] * RA[:, 0] + qd[5] * RC[:, 1]
            s = vG + np.cross(w, arm)
            return [s.dot(RF[:, (k + 1) % 3]), s.dot(RF[:, (k + 2) % 3])]
        A = np.array([slip(np.eye(6)[j]) for j in range(6)]).T
        states.append({"q": q.tolist(), "qd": qd.tolist(), "contact": float(contact), "slip_rows": A.tolist(), "slip": slip(qd)})
    out[key] = states
with open(os.path.join(ROOT, "tests", "reference", "rolling_planes.json"), "w") as f:
    json.dump(out, f, indent=1)
    f.write("\n")
