"""A crank's flywheel and counterweight from its driving torque and shaking force over a turn (pure numpy).

**Flywheel.** Over a turn at mean speed w the driver's torque T(theta) does work against the linkage's loads and its
changing kinetic energy; the energy the speed must absorb is the fluctuation dE = max - min over the turn of
E(theta) = integral of (T - T_mean) dtheta. A crank whose total inertia is I keeps its speed within a coefficient
of fluctuation Cs = (w_max - w_min) / w_mean when I = dE / (Cs w^2) (to first order in Cs). The linkage itself
brings its mean generalised inertia J_mean (:mod:`linkgen.kinematics.inertia`), so the flywheel adds
I - J_mean. T is sampled uniformly over the turn and integrated by its Fourier series (exact for a band-limited
torque; spectrally accurate otherwise).

**Counterweight.** The shaking force of a crank turning at constant speed is periodic; its first harmonic, as a
complex number F = Fx + i Fy, is P e^{i theta} + Q e^{-i theta}: P turns with the crank, Q against it. A mass m at
radius r on the crank, at angle beta from the crank's line (counter-clockwise), shakes the frame with
m r w^2 e^{i(theta + beta)}: it cancels P (m r = |P| / w^2, beta = arg(-P)) and cannot touch Q, which is what is
left of the first harmonic. Angles here are the crank's input angle theta (rad, the direction of its line).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Fluctuation:
    """The energy fluctuation over a turn: ``energy`` dE (J), the mean torque (N*m), and the crank angles (rad)
    where the energy above the mean's work is greatest and least."""

    energy: float
    mean_torque: float
    at_max: float
    at_min: float


def fluctuation(theta: np.ndarray, torque: np.ndarray, upsample: int = 16) -> Fluctuation:
    """The energy fluctuation of the torque ``torque`` (N*m) sampled at ``theta`` (rad), uniform over one turn
    without its end (theta[0] + 2 pi is theta[0] again); E's extremes searched on a grid ``upsample`` times
    finer."""
    n = len(theta)
    c = np.fft.rfft(torque) / n
    k = np.arange(len(c))
    e = np.zeros_like(c)
    e[1:] = c[1:] / (1j * k[1:])
    if n % 2 == 0:
        e[-1] = 0.0                          # the Nyquist term has no sine part to integrate
    m = n * upsample
    fine = np.fft.irfft(e * m, m)
    hi, lo = int(np.argmax(fine)), int(np.argmin(fine))
    step = 2 * math.pi / m
    return Fluctuation(float(fine[hi] - fine[lo]), float(c[0].real), float(theta[0] + hi * step),
                       float(theta[0] + lo * step))


def flywheel_inertia(energy: float, fluctuation_coefficient: float, speed: float, own: float) -> tuple[float, float]:
    """The total inertia at the crank (kg*m^2) that keeps the speed ``speed`` (rad/s) within
    ``fluctuation_coefficient`` for an energy fluctuation ``energy`` (J), and the flywheel's part of it: the total
    less the linkage's own mean inertia ``own`` (kg*m^2; 0 when the linkage alone is enough)."""
    total = energy / (fluctuation_coefficient * speed**2)
    return total, max(0.0, total - own)


@dataclass(frozen=True)
class Counterweight:
    """The counterweight that cancels the forward-turning first harmonic of the shaking force: ``mass_radius``
    m r (kg*m) at ``angle`` (rad, counter-clockwise from the crank's line), and the first harmonic's forward and
    backward amplitudes |P| and |Q| (N); the shaking force's peak before and after (N)."""

    mass_radius: float
    angle: float
    forward: float
    backward: float
    peak_before: float
    peak_after: float


def counterweight(theta: np.ndarray, shaking: np.ndarray, speed: float) -> Counterweight:
    """The crank's counterweight for the shaking force ``shaking`` (n, 2) N at crank angles ``theta`` (rad, uniform
    over a turn without its end) at constant ``speed`` (rad/s)."""
    z = shaking[:, 0] + 1j * shaking[:, 1]
    n = len(theta)
    forward = complex(np.sum(z * np.exp(-1j * theta)) / n)
    backward = complex(np.sum(z * np.exp(1j * theta)) / n)
    mass_radius = abs(forward) / speed**2 if speed > 0 else 0.0
    angle = float(np.angle(-forward)) if abs(forward) > 0 else 0.0
    after = z - forward * np.exp(1j * theta)
    return Counterweight(mass_radius, angle, abs(forward), abs(backward), float(np.abs(z).max()),
                         float(np.abs(after).max()))
