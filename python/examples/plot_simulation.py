"""Plot a gyrostat simulation with matplotlib: the momentum exchange of README's worked example
(the seed's body (6, 4, 3) spinning about its intermediate axis, held by a reaction wheel that a
constant motor torque spins down, handing its momentum to the body).

    pip install ./python matplotlib
    python3 python/examples/plot_simulation.py [--out momentum-exchange.png]

Writes a PNG: body rates, wheel speed, the drift of the conserved quantities, and the path of
the momentum J on the sphere |J| = const (projected on the J1-J3 plane).
"""

from __future__ import annotations

import argparse

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt
import numpy as np

import gyrostat


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="momentum-exchange.png", help="PNG to write")
    ap.add_argument("--steps", type=int, default=20000)
    args = ap.parse_args()

    sim = gyrostat.simulate(
        inertia=(6, 4, 3),
        omega=(0.05, 1, 0.01),
        wheels=[(0, 1, 0, 0.05, 60)],  # axis y, 0.05 kg m^2, 60 rad/s
        wheel_torque=(-0.015,),  # N m, held
        dt=0.01,
        steps=args.steps,
        every=10,
        integrator="yoshida4",
    )
    m = sim.monitors
    lab = gyrostat.Rotation.from_quat(sim.q, scalar_first=True).apply(sim.momentum)
    lab_drift = np.linalg.norm(lab - lab[0], axis=1) / np.linalg.norm(lab[0])
    norm = np.linalg.norm(sim.momentum, axis=1)

    fig, ax = plt.subplots(2, 2, figsize=(11, 7), constrained_layout=True)
    for i, name in enumerate(["w1", "w2", "w3"]):
        ax[0, 0].plot(sim.t, sim.omega[:, i], label=name)
    ax[0, 0].set(xlabel="t (s)", ylabel="body rate (rad/s)", title="body rates")
    ax[0, 0].legend()
    ax[0, 1].plot(sim.t, sim.wheel_speeds[:, 0], color="tab:purple")
    ax[0, 1].set(xlabel="t (s)", ylabel="rad/s", title="wheel speed (relative to the body)")
    ax[1, 0].semilogy(sim.t[1:], lab_drift[1:] + 1e-17, label="lab momentum R(q) J")
    ax[1, 0].semilogy(sim.t[1:], np.abs(norm[1:] / norm[0] - 1) + 1e-17, label="|J|")
    ax[1, 0].set(xlabel="t (s)", ylabel="relative drift", title="conserved quantities (internal torque only)")
    ax[1, 0].legend()
    j = sim.momentum / norm[:, None]
    ax[1, 1].plot(j[:, 0], j[:, 2], lw=0.6)
    ax[1, 1].plot(j[0, 0], j[0, 2], "o", color="k", label="start: +J2 held by the wheel")
    ax[1, 1].set(xlabel="J1/|J|", ylabel="J3/|J|", title="the momentum's path (polhode)", aspect="equal")
    ax[1, 1].legend(loc="lower left", fontsize=8)
    fig.suptitle(
        "gyrostat: momentum exchange with a reaction wheel, yoshida4, dt = 0.01 s "
        f"(max lab-momentum drift {m['lab_momentum_drift_max']:.1e})"
    )
    fig.savefig(args.out, dpi=110)
    print(f"plot written to {args.out}")


if __name__ == "__main__":
    main()
