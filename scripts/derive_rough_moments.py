#!/usr/bin/env python3
"""Collisional moments of rough spheres for the Sonine-truncated distribution, exactly (sympy).

Prints the C++ body of theory::rough::collisional_moments (src/theory/rough.cpp). The derivation is the
one of Santos, Kremer and dos Santos, Phys. Fluids 23, 030604 (2011) (docs/rough-spheres.md#rough_sonine):
one species, units m = sigma = T_tr = 1, I = kappa/4, T_rot = theta; the distribution
  f = f_M(c) f_M(w) [1 + a20 S2(c^2) + a02 S2(w^2) + a11 S1(c^2) S1(w^2)],
  c = v/sqrt(2 T_tr/m), w = omega/sqrt(2 T_rot/I), S1(x) = 3/2 - x, S2(x) = 15/8 - 5x/2 + x^2/2,
kept to first order in the cumulants (the products f1 f2 linearised). For psi in v^2, w^2, v^4, w^4, v^2 w^2
(w here the angular velocity omega) it computes the rate of change of <psi> per Maxwellian collision,
  R_psi = (1/nu_M) d<psi>/dt = (sqrt(pi)/2) E[Theta(g.e) (g.e) (psi1' + psi2' - psi1 - psi2)],
nu_M = 4 sqrt(pi) n sigma^2 sqrt(T_tr/m), as R_psi = R0 + R20 a20 + R02 a02 + R11 a11. The rule is
dsmc/rules.hpp RoughRule: J = (1 + alpha)(g.e) e + (1 + beta) K g_ct, v1 -= J/2, v2 += J/2,
omega1,2 -= (1/kappa) e x J, g_c = g - e x (omega1 + omega2)/2, K = kappa/(1 + kappa). The coefficients are
polynomials in alpha, h = K (1 + beta) (= 2 eta), q = 1/kappa and theta. The expectation is exact:
velocities in centre-of-mass form (V, g, Omega = (w1 + w2)/2, delta = w1 - w2 are independent Gaussians),
e = z, and every monomial integrated in closed form (half-space moments for g_z).

Needs python3-sympy, which scripts/install-deps.sh does not install: the script is a derivation kept with the
code, not part of the build, the tests or the figures.

Usage: scripts/derive_rough_moments.py   (about 4 minutes). tests/rough_test.cpp checks the printed
coefficients against their smooth and Maxwellian limits (by hand) and against a Monte Carlo estimate.
"""
import sympy as sp

al, be, K, q, th = sp.symbols('alpha beta K q theta', positive=True)
h = sp.Symbol('h')
V, g, Om, dl = sp.symbols('Vx Vy Vz'), sp.symbols('gx gy gz'), sp.symbols('Ox Oy Oz'), sp.symbols('dx dy dz')
VARS = V + g + Om + dl


def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def sq(a): return dot(a, a)


E = (0, 0, 1)
R2 = 4 * th * q  # <omega_x^2> = T_rot/I = 4 theta/kappa


def collide(gv, Ov):
    """g' and Omega' of RoughRule (sigma = m = 1)."""
    gc = tuple(x - y for x, y in zip(gv, cross(E, Ov)))
    gct = tuple(x - dot(gc, E) * y for x, y in zip(gc, E))
    J = tuple((1 + al) * gv[2] * y + (1 + be) * K * x for x, y in zip(gct, E))
    return tuple(x - y for x, y in zip(gv, J)), tuple(x - y * q for x, y in zip(Ov, cross(E, J)))


def particles(Vv, gv, Ov, dv):
    half = lambda a, b, s: tuple(x + s * y / 2 for x, y in zip(a, b))
    return half(Vv, gv, 1), half(Vv, gv, -1), half(Ov, dv, 1), half(Ov, dv, -1)


PSI = {
    'v2': lambda v1, v2, w1, w2: sq(v1) + sq(v2),
    'w2': lambda v1, v2, w1, w2: sq(w1) + sq(w2),
    'v4': lambda v1, v2, w1, w2: sq(v1) ** 2 + sq(v2) ** 2,
    'w4': lambda v1, v2, w1, w2: sq(w1) ** 2 + sq(w2) ** 2,
    'v2w2': lambda v1, v2, w1, w2: sq(v1) * sq(w1) + sq(v2) * sq(w2),
}
S1 = lambda x: sp.Rational(3, 2) - x
S2 = lambda x: sp.Rational(15, 8) - sp.Rational(5, 2) * x + x ** 2 / 2


def weights(v1, v2, w1, w2, r2):
    c1, c2, W1, W2 = sq(v1) / 2, sq(v2) / 2, sq(w1) / (2 * r2), sq(w2) / (2 * r2)
    return {'0': 1, 'a20': S2(c1) + S2(c2), 'a02': S2(W1) + S2(W2), 'a11': S1(c1) * S1(W1) + S1(c2) * S1(W2)}


VARIANCE = {**{x: sp.Rational(1, 2) for x in V}, **{x: 2 for x in g}, **{x: R2 / 2 for x in Om}, **{x: 2 * R2 for x in dl}}


def expectation(expr):
    """E[Theta(g_z) g_z expr] over the independent Gaussians, monomial by monomial."""
    total = 0
    for powers, coef in sp.Poly(sp.expand(expr), *VARS).terms():
        value = coef
        for x, k in zip(VARS, powers):
            s2 = VARIANCE[x]
            if x == g[2]:  # E[Theta(x) x^n] = s^n 2^(n/2) Gamma((n + 1)/2)/(2 sqrt(pi))
                n = k + 1
                value *= sp.sqrt(s2) ** n * 2 ** sp.Rational(n, 2) * sp.gamma(sp.Rational(n + 1, 2)) / (2 * sp.sqrt(sp.pi))
            elif k % 2:
                value = 0
                break
            else:
                value *= sp.factorial2(k - 1) * s2 ** (k // 2) if k else 1
        total += value
    return total


def derive():
    before = particles(V, g, Om, dl)
    gp, Op = collide(g, Om)
    after = particles(V, gp, Op, dl)
    w = weights(*before, R2)
    out = {}
    for name, psi in PSI.items():
        change = sp.expand(psi(*after) - psi(*before))
        for key, weight in w.items():
            value = sp.sqrt(sp.pi) / 2 * expectation(change * weight)
            out[(name, key)] = sp.factor(sp.expand(sp.simplify(value).subs(K, h / (1 + be))))
    return out


def main():
    out = derive()
    names = {'0': 'zero', 'a20': 'a20', 'a02': 'a02', 'a11': 'a11'}
    for name in PSI:
        print(f'  // R_{name}')
        for key in ('0', 'a20', 'a02', 'a11'):
            print(f'  m.{name}.{names[key]} = {sp.ccode(out[(name, key)], standard="c99")};')


if __name__ == '__main__':
    main()
