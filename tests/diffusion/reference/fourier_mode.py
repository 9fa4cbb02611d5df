#!/usr/bin/python3
"""Symbol of the continuous bond-based PD diffusion operator.

The kernel of Models::DiffusionKernel: J = kappa omega(|xi|/delta) (C' - C)
/ |xi|^q, kappa by flux matching
    kappa = 2 d K / int_B omega r^(2-q) dV
          = 2 d K / (S_{d-1} delta^(d+2-q) M_{d+1-q}),
    M_j = int_0^1 omega(s) s^j ds,  S_0 = 2, S_1 = 2 pi, S_2 = 4 pi.

For C = exp(i k.x) the operator L[C](x) = int_B kappa omega (C(x+xi) -
C(x)) / |xi|^q dV_xi gives L[C] = -lambda(|k|) C with

    lambda(k) = kappa int_B omega(|xi|/delta) (1 - cos(k.xi)) / |xi|^q dV

(the sine part cancels: the ball is symmetric). Averaging cos(k.xi) over
the sphere |xi| = r gives A_d(k r): cos(k r) in 1D, J0(k r) in 2D,
sin(k r)/(k r) in 3D, so with z = |k| delta

    lambda / (K |k|^2) = 2 d / (z^2 M_{d+1-q})
                         * int_0^1 omega(s) (1 - A_d(z s)) s^(d-1-q) ds.

Small z: lambda = K k^2 [1 - z^2 M_{d+3-q} / (4 (d+2) M_{d+1-q}) + O(z^4)].
The integral exists for d + 1 - q > -1, i.e. q <= 2 in 1D (q = 3 diverges
in 1D as it does for kappa), every q = 0..3 in 2D and 3D.

Since lambda depends on |k| only, sin(k1 x) sin(k2 y) [sin(k3 z)] (a sum of
exponentials exp(i (+-k1 x +- k2 y ...)) of the same |k|) is an
eigenfunction too, and C = exp(-lambda t) sin(k1 x) sin(k2 y) [sin(k3 z)]
solves dC/dt = L[C] at every x whose horizon lies in the region where C is
given by that formula.

The discrete operator of the code (one-point rule, exact partial volumes
beta_j h^d, kernel at the neighbour's centre, omega clipped at 0, the own
cell left out) on a uniform grid h = delta/m has the symbol
    lambda_h(k) = sum_j kappa max(omega(|xi_j|/delta), 0) / |xi_j|^q
                  beta_j h^d (1 - cos(k.xi_j)),
exact for a node whose neighbourhood is complete; --weights takes the
offsets and beta_j as printed by `perideal-weights --dim D --m-ratio M`
(spacing 1) and prints lambda_h too, so that the quadrature error of a run
can be predicted: |exp(-(lambda_h - lambda) T) - 1| in the interior.

Usage:
  fourier_mode.py --dim D --q Q --omega constant|conical|gaussian
                  --delta DELTA --K K --k K1,K2[,K3] [--digits 30]
                  [--weights CSV --m-ratio M]
  fourier_mode.py --self-check
prints lambda, K |k|^2, their ratio and kappa (--digits significant
digits) [and lambda_h, lambda_h / lambda].
"""
import argparse
import sys

import mpmath as mp

SPHERE = {1: 2, 2: 2 * mp.pi, 3: 4 * mp.pi}


def omega_function(name):
    if name == "constant":
        return lambda s: mp.mpf(1)
    if name == "conical":
        return lambda s: 1 - s
    if name == "gaussian":
        return lambda s: mp.exp(-s * s)
    raise ValueError("unknown influence function " + name)


def one_minus_average(dim, x):
    """1 - A_d(x), A_d the average of cos(k.xi) over the sphere |k xi| = x,
    by its series for small x (no cancellation)."""
    if abs(x) < mp.mpf("1e-3"):
        # 1 - A_d(x) = sum_{n>=1} (-1)^(n+1) x^(2n) / (2^n n! d (d+2)...(d+2n-2))
        term, total, n = mp.mpf(1), mp.mpf(0), 1
        while True:
            term = term * x * x / (2 * n * (dim + 2 * n - 2))
            total += term if n % 2 == 1 else -term
            if abs(term) < mp.eps * abs(total):
                return total
            n += 1
    if dim == 1:
        return 1 - mp.cos(x)
    if dim == 2:
        return 1 - mp.besselj(0, x)
    return 1 - mp.sin(x) / x


def moment(omega, j):
    return mp.quad(lambda s: omega(s) * s**j, [0, 1])


def kappa(dim, q, omega, delta, K):
    if dim + 1 - q < 0:
        raise ValueError("q = %d in %dD: the flux-matching integral diverges"
                         % (q, dim))
    return 2 * dim * K / (SPHERE[dim] * delta ** (dim + 2 - q)
                          * moment(omega, dim + 1 - q))


def shape_integral(dim, q, omega, z):
    """int_0^1 omega(s) (1 - A_d(z s)) s^(d-1-q) ds."""
    # Split at multiples of pi/z: the integrand oscillates for large z.
    points = [mp.mpf(0)]
    if z > 0:
        n = int(mp.floor(z / mp.pi))
        points += [mp.pi * j / z for j in range(1, n + 1) if mp.pi * j / z < 1]
    points.append(mp.mpf(1))
    return mp.quad(lambda s: omega(s) * one_minus_average(dim, z * s)
                   * s ** (dim - 1 - q), points)


def symbol(dim, q, omega_name, delta, K, k):
    """lambda(|k|) of the continuous operator."""
    omega = omega_function(omega_name)
    knorm = mp.sqrt(sum(mp.mpf(c) ** 2 for c in k))
    z = knorm * delta
    return (kappa(dim, q, omega, delta, K) * SPHERE[dim] * delta ** (dim - q)
            * shape_integral(dim, q, omega, z))


def discrete_symbol(dim, q, omega_name, delta, K, k, weights, m):
    """lambda_h of the one-point rule with the offsets and beta of
    perideal-weights (CSV: x,y[,z],beta, spacing 1)."""
    omega = omega_function(omega_name)
    kap = kappa(dim, q, omega, delta, K)
    h = delta / m
    total = mp.mpf(0)
    with open(weights) as f:
        header = f.readline().strip().split(",")
        if len(header) != dim + 1:
            raise ValueError("%s: not a %dD weights file" % (weights, dim))
        for line in f:
            values = [mp.mpf(v) for v in line.split(",")]
            xi = [h * v for v in values[:dim]]
            r = mp.sqrt(sum(c * c for c in xi))
            w = max(omega(r / delta), 0)
            total += (kap * w / r**q * values[dim] * h**dim
                      * (1 - mp.cos(sum(a * b for a, b in zip(k, xi)))))
    return total


# Closed forms of F_p(z) = int_0^1 (1 - A_d(z s)) s^(d-1-p) ds (constant
# influence); the conical influence 1 - s gives F_q - F_{q-1}.
def closed_constant(dim, p, z):
    Si, Cin = mp.si, lambda x: mp.euler + mp.log(x) - mp.ci(x)
    J0, J1 = lambda x: mp.besselj(0, x), lambda x: mp.besselj(1, x)
    table = {
        (1, -1): lambda: mp.mpf(1) / 2 - mp.sin(z) / z - (mp.cos(z) - 1) / z**2,
        (1, 0): lambda: 1 - mp.sin(z) / z,
        (1, 1): lambda: Cin(z),
        (1, 2): lambda: z * Si(z) - 1 + mp.cos(z),
        (2, -1): lambda: mp.mpf(1) / 3 - J1(z) / z + mp.pi / (2 * z**2) * (
            J1(z) * mp.struveh(0, z) - J0(z) * mp.struveh(1, z)),
        (2, 0): lambda: mp.mpf(1) / 2 - J1(z) / z,
        (2, 1): lambda: 1 - (z * J0(z) + mp.pi * z / 2 * (
            J1(z) * mp.struveh(0, z) - J0(z) * mp.struveh(1, z))) / z,
        (2, 2): lambda: z**2 / 8 * mp.hyp2f3(1, 1, 2, 2, 2, -z**2 / 4),
        (3, -1): lambda: mp.mpf(1) / 4 - (  # int s^3 (1 - sin(zs)/(zs)) ds
            2 * z * mp.sin(z) - (z**2 - 2) * mp.cos(z) - 2) / z**4,
        (3, 0): lambda: mp.mpf(1) / 3 - (mp.sin(z) - z * mp.cos(z)) / z**3,
        (3, 1): lambda: mp.mpf(1) / 2 - (1 - mp.cos(z)) / z**2,
        (3, 2): lambda: 1 - Si(z) / z,
        (3, 3): lambda: Cin(z) + mp.sin(z) / z - 1,
    }
    return table[(dim, p)]() if (dim, p) in table else None


def self_check():
    mp.mp.dps = 30
    failures = 0

    def report(name, a, b, tol):
        nonlocal failures
        ok = abs(a - b) <= tol * max(abs(b), 1)
        failures += not ok
        print("%-58s %s %s %s" % (name, mp.nstr(a, 18), mp.nstr(b, 18),
                                  "ok" if ok else "FAIL"))

    # The brief's check: 1D, omega = 1, q = 0.
    for z in ["0.3", "1", "2.5", "7"]:
        z = mp.mpf(z)
        ratio = symbol(1, 0, "constant", mp.mpf(1), 1, [z]) / z**2
        report("1D const q=0, z=%s: 6(z - sin z)/z^3" % mp.nstr(z, 3), ratio,
               6 * (z - mp.sin(z)) / z**3, mp.mpf("1e-25"))
    # Closed forms against the 1D integrals (constant and conical).
    for dim in (1, 2, 3):
        for q in range(0, 4):
            if dim + 1 - q < 0:
                continue
            for z in ("0.7", "3.3"):
                z = mp.mpf(z)
                for name in ("constant", "conical"):
                    om = omega_function(name)
                    fq = closed_constant(dim, q, z)
                    fq1 = closed_constant(dim, q - 1, z)
                    if fq is None or (name == "conical" and fq1 is None):
                        continue
                    closed = fq if name == "constant" else fq - fq1
                    report("closed form %dD %s q=%d z=%s" % (
                        dim, name, q, mp.nstr(z, 2)),
                        shape_integral(dim, q, om, z), closed, mp.mpf("1e-25"))
    # Long waves: lambda -> K k^2 (flux matching) with the z^2 correction.
    for dim in (1, 2, 3):
        for q in range(0, 4):
            if dim + 1 - q < 0:
                continue
            for name in ("constant", "conical", "gaussian"):
                om = omega_function(name)
                z = mp.mpf("1e-2")
                ratio = symbol(dim, q, name, mp.mpf(1), 1, [z]) / z**2
                series = 1 - z**2 * moment(om, dim + 3 - q) / (
                    4 * (dim + 2) * moment(om, dim + 1 - q))
                report("long waves %dD %s q=%d" % (dim, name, q), ratio,
                       series, mp.mpf("1e-9"))
    # Independent check in Cartesian coordinates (double precision, k off
    # the axes): lambda = kappa int_B omega (1 - cos k.xi) / |xi|^q.
    import numpy as np
    from scipy import integrate
    for dim, q, name, k in ((2, 1, "constant", (2.0, 1.3)),
                            (2, 2, "conical", (0.9, 3.1)),
                            (3, 1, "conical", (1.5, 2.0, 2.5)),
                            (3, 3, "constant", (0.7, 1.1, 3.2))):
        delta = 1.0
        om = omega_function(name)
        kap = float(kappa(dim, q, om, mp.mpf(delta), 1))
        w = {"constant": lambda r: 1.0, "conical": lambda r: 1.0 - r}[name]
        if dim == 2:
            # polar: the angular integral numerically (not the J0 identity)
            f = lambda th, r: w(r) * (1 - np.cos(r * (k[0] * np.cos(th) + k[1] * np.sin(th)))) * r ** (1 - q)
            val = integrate.dblquad(f, 0, delta, 0, 2 * np.pi,
                                    epsabs=1e-12, epsrel=1e-11)[0]
        else:
            f = lambda ph, th, r: w(r) * (1 - np.cos(r * (
                k[0] * np.sin(th) * np.cos(ph) + k[1] * np.sin(th) * np.sin(ph)
                + k[2] * np.cos(th)))) * r ** (2 - q) * np.sin(th)
            val = integrate.tplquad(f, 0, delta, 0, np.pi, 0, 2 * np.pi,
                                    epsabs=1e-10, epsrel=1e-9)[0]
        report("Cartesian %dD %s q=%d k=%s" % (dim, name, q, k),
               mp.mpf(kap * val), symbol(dim, q, name, mp.mpf(delta), 1, k),
               mp.mpf("1e-7"))
    print("self-check:", "FAIL (%d)" % failures if failures else "all ok")
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--dim", type=int, choices=(1, 2, 3))
    parser.add_argument("--q", type=int, choices=(0, 1, 2, 3))
    parser.add_argument("--omega", default="constant",
                        choices=("constant", "conical", "gaussian"))
    parser.add_argument("--delta", type=str, help="horizon (a number or an "
                        "mpmath expression such as 1/8)")
    parser.add_argument("--K", type=str, default="1")
    parser.add_argument("--k", type=str, help="wave vector k1,k2[,k3]; "
                        "'pi' allowed, e.g. 2*pi,pi")
    parser.add_argument("--digits", type=int, default=30)
    parser.add_argument("--weights", help="CSV of perideal-weights for "
                        "--m-ratio: also print the discrete symbol")
    parser.add_argument("--m-ratio", type=str, help="delta / h of --weights")
    parser.add_argument("--self-check", action="store_true")
    args = parser.parse_args()
    if args.self_check:
        return self_check()
    if None in (args.dim, args.q, args.delta, args.k):
        parser.error("--dim, --q, --delta and --k are required")
    mp.mp.dps = args.digits + 10
    ev = lambda text: mp.mpf(eval(text, {"pi": mp.pi, "sqrt": mp.sqrt}))
    k = [ev(c) for c in args.k.split(",")]
    if len(k) != args.dim:
        parser.error("--k needs %d components" % args.dim)
    delta, K = ev(args.delta), ev(args.K)
    lam = symbol(args.dim, args.q, args.omega, delta, K, k)
    classical = K * sum(c * c for c in k)
    d = args.digits
    print("lambda = %s" % mp.nstr(lam, d))
    print("K|k|^2 = %s" % mp.nstr(classical, d))
    print("ratio  = %s" % mp.nstr(lam / classical, d))
    print("kappa  = %s" % mp.nstr(kappa(args.dim, args.q,
                                        omega_function(args.omega), delta, K), d))
    if args.weights:
        if args.m_ratio is None:
            parser.error("--weights needs --m-ratio")
        lam_h = discrete_symbol(args.dim, args.q, args.omega, delta, K, k,
                                args.weights, ev(args.m_ratio))
        print("lambda_h = %s" % mp.nstr(lam_h, 16))
        print("lambda_h / lambda = %s" % mp.nstr(lam_h / lam, 16))
    return 0


if __name__ == "__main__":
    sys.exit(main())
