#!/usr/bin/python3
"""Independent evaluation of the MMG standard model (Yasukawa & Yoshimura 2015,
J. Mar. Sci. Technol. 20:37-52, eqs. 4-25) for KVLCC2 (L7 model), written
directly from the paper's equations in their original form (u_R with
sqrt(1 + 8 K_T / (pi J^2))), without kelvin's code. It prints the reference
numbers that tests/simulator/mmg_model_test.cc asserts at a few states.
Run: /usr/bin/python3 tests/simulator/mmg_reference.py
"""
import math

rho, L, d, B, disp, xG = 1025.0, 7.0, 0.46, 1.27, 3.27, 0.25
hull = dict(R0=0.022, Xvv=-0.040, Xvr=0.002, Xrr=0.011, Xvvvv=0.771,
            Yv=-0.315, Yr=0.083, Yvvv=-1.607, Yvvr=0.379, Yvrr=-0.391, Yrrr=0.008,
            Nv=-0.137, Nr=-0.049, Nvvv=-0.030, Nvvr=-0.294, Nvrr=0.055, Nrrr=-0.013)
Dp, tP, wP0, k0, k1, k2, xP = 0.216, 0.220, 0.40, 0.2931, -0.2753, -0.1385, -0.48
C1, C2p, C2m = 2.0, 1.6, 1.1
AR, HR, tR, aH, xHp, xRp = 0.0539, 0.345, 0.387, 0.312, -0.464, -0.5
gRm, gRp, lRp, eps, kap, fa = 0.395, 0.640, -0.710, 1.09, 0.50, 2.747


def forces(u, vm, r, delta, n):
    U = math.sqrt(u * u + vm * vm)
    v, rp = vm / U, r * L / U
    beta = math.atan(-vm / u)
    h = hull
    XH = 0.5 * rho * L * d * U**2 * (-h['R0'] + h['Xvv'] * v**2 + h['Xvr'] * v * rp + h['Xrr'] * rp**2 + h['Xvvvv'] * v**4)
    YH = 0.5 * rho * L * d * U**2 * (h['Yv'] * v + h['Yr'] * rp + h['Yvvv'] * v**3 + h['Yvvr'] * v**2 * rp + h['Yvrr'] * v * rp**2 + h['Yrrr'] * rp**3)
    NH = 0.5 * rho * L**2 * d * U**2 * (h['Nv'] * v + h['Nr'] * rp + h['Nvvv'] * v**3 + h['Nvvr'] * v**2 * rp + h['Nvrr'] * v * rp**2 + h['Nrrr'] * rp**3)
    betaP = beta - xP * rp
    C2 = C2p if betaP > 0 else C2m
    wP = 1 - (1 - wP0) * (1 + (1 - math.exp(-C1 * abs(betaP))) * (C2 - 1))
    J = u * (1 - wP) / (n * Dp)
    KT = k0 + k1 * J + k2 * J * J
    T = rho * n * n * Dp**4 * KT
    XP = (1 - tP) * T
    etaR = Dp / HR
    uR = eps * u * (1 - wP) * math.sqrt(etaR * (1 + kap * (math.sqrt(1 + 8 * KT / (math.pi * J * J)) - 1))**2 + (1 - etaR))
    betaR = beta - lRp * rp
    gR = gRm if betaR < 0 else gRp
    vR = U * gR * betaR
    aR = delta - math.atan(vR / uR)
    FN = 0.5 * rho * AR * (uR**2 + vR**2) * fa * math.sin(aR)
    XR = -(1 - tR) * FN * math.sin(delta)
    YR = -(1 + aH) * FN * math.cos(delta)
    NR = -(xRp * L + aH * xHp * L) * FN * math.cos(delta)
    return dict(XH=XH, YH=YH, NH=NH, XP=XP, T=T, wP=wP, J=J, KT=KT, uR=uR, vR=vR, aR=aR, FN=FN,
                XR=XR, YR=YR, NR=NR)


STATES = [
    ("straight", 1.179, 0.0, 0.0, 0.0, 11.85),
    ("drift_turn_stbd_rudder", 1.10, -0.08, 0.05, math.radians(15.0), 11.85),
    ("port_turn_port_rudder", 0.90, 0.06, -0.07, math.radians(-35.0), 10.0),
]

if __name__ == '__main__':
    for name, u, v, r, delta, n in STATES:
        f = forces(u, v, r, delta, n)
        print(name, ", ".join(f"{k}={f[k]:.12e}" for k in f))
