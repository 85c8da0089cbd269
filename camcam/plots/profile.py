"""The cam plot: the cam drawn at cam angle 0 (or its developed groove), with the
pressure angle and the radius of curvature over the revolution."""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.analysis import convex_curvature, flat_radius
from camcam.geometry.build import BuiltCam
from camcam.geometry.cylindrical import CylindricalCam
from camcam.plots.render import TITLE_Y, Circle, figure, png_bytes
from camcam.plots.stacked import angle_axis

__all__ = ["cam_png", "LAYOUT"]

#: Figure margins (fractions): the cam drawing left, pressure angle and radius of curvature right.
LAYOUT = dict(left=0.065, right=0.975, bottom=0.10, top=0.885, hspace=0.3, wspace=0.17)

#: Plotted radii of curvature are clipped to this multiple of the base radius (flat parts are infinite).
RHO_CLIP = 4.0


def _draw_disc(ax, cam) -> None:
    ax.plot(*cam.profile.polyline().T, color="C0", lw=1.6, label="profile")
    if hasattr(cam, "flanks"):
        ax.plot(*cam.flanks[1].polyline().T, color="C0", lw=1.6)
    if cam.pitch is not None:
        ax.plot(*cam.pitch.polyline().T, color="C1", lw=0.9, ls="--", label="pitch curve")
    a = np.linspace(0, 2 * math.pi, 361)
    ax.plot(cam.base_radius * np.cos(a), cam.base_radius * np.sin(a), color="0.6", lw=0.8, ls=":", label="base circle")
    # the follower at a few program angles, drawn in the cam frame
    for k, th in enumerate(np.radians([0.0, 90.0, 180.0, 270.0])):
        if cam.pitch is not None:
            c = cam.pitch.evaluate([th])[0]
            ax.add_patch(Circle(c, cam.roller_radius, fill=False, color="C2", lw=0.8, label="roller" if k == 0 else None))
        else:
            q = cam.profile.evaluate([th])[0]
            n = cam.normal([th])[0]
            tang = np.array([-n[1], n[0]]) * 0.25 * cam.base_radius
            ax.plot(*np.array([q - tang, q + tang]).T, color="C2", lw=1.2, label="face" if k == 0 else None)
    ax.plot([0], [0], "k+")
    ax.set_aspect("equal")
    ax.set_title("cam at cam angle 0 (mm)", y=TITLE_Y)
    ax.legend(fontsize=7, loc="upper right")


def _draw_developed(ax, cam: CylindricalCam) -> None:
    for rho, ls in ((cam.bottom_radius, "-"), (cam.base_radius, "--")):
        for i in (0, 1):
            u, x = cam.developed_flank(i, rho).polyline().T
            ax.plot(u, x, color="C0", ls=ls, lw=1.0, label=f"flanks at r = {rho:g}" if i == 0 else None)
    u, x = cam.developed_centre(cam.reference_radius).polyline().T
    ax.plot(u, x, color="C1", lw=0.8, ls=":", label="centre line")
    ax.set_xlabel("developed length u [mm]")
    ax.set_ylabel("axial x [mm]")
    ax.set_title("developed groove", y=TITLE_Y)
    ax.legend(fontsize=7)


def cam_png(built: BuiltCam, title: str = "") -> bytes:
    cam, an = built.cam, built.analysis
    fig = figure(figsize=(11, 6))
    ax0 = fig.add_subplot(1, 2, 1)
    ax1, ax2 = fig.add_subplot(2, 2, 2), fig.add_subplot(2, 2, 4)
    cyl = isinstance(cam, CylindricalCam)
    (_draw_developed if cyl else _draw_disc)(ax0, cam)
    br = cam.breaks
    t = np.concatenate([np.linspace(a, b, 240) for a, b in zip(br, br[1:])])
    deg = np.degrees(t)
    ax1.plot(deg, np.degrees(cam.pressure_angle(t).value), color="C3")
    p = an.max_pressure_angle_deg
    ax1.axvline(p.angle_deg, color="0.5", lw=0.7, ls="--")
    ax1.set_ylabel("pressure angle [deg]")
    ax1.set_title(f"max |pressure angle| {p.value:.3f}° at {p.angle_deg:.2f}°", fontsize=9, y=TITLE_Y)
    if cyl:
        k = convex_curvature(cam.developed_centre(cam.bottom_radius), 1, t)[0]
        with np.errstate(divide="ignore"):
            rho = 1.0 / np.abs(k) - cam.roller_radius
    elif cam.pitch is None:
        rho = flat_radius(cam, t)[0]
    else:
        rho = 1.0 / convex_curvature(cam.profile, cam.sigma, t)[0]
    rho = np.clip(rho, -RHO_CLIP * cam.base_radius, RHO_CLIP * cam.base_radius)
    ax2.plot(deg, rho, color="C4")
    c = an.profile
    ax2.set_ylabel("radius of curvature [mm]")
    ax2.set_title(f"min convex radius of curvature {c.describe()}", fontsize=9, y=TITLE_Y)
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3)
    angle_axis((ax1, ax2), step_deg=60.0, grid_alpha=0.3)  # the angles labelled once, under the lower one
    fig.suptitle(title)
    # fixed margins, not tight_layout (a second draw); tests/plots check nothing is cut off
    fig.subplots_adjust(**LAYOUT)
    return png_bytes(fig)
