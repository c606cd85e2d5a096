"""SymPy doing the derivations impactcheck's exact algebra does, timed side by side:

1. the Adomian terms a0..a3 of 000_92d54b11128ea1ec.txt (18)-(23) with every symbol free:
   a_{k+1} = -A8 II[L(alpha) - L(gamma)][A_k] - A9 II[L(alpha) - L(gamma)][B_k],
   A_k = sum a_i a_{k-i}, B_k = dA_k/dt, L(d)[g] = exp(-d t) int_0^t exp(d s) g(s) ds, II the
   double integral from 0; each term brought to the same canonical form impactcheck keeps (a sum
   of t^k exp(r t) with cancelled rational coefficients);
2. the Galerkin coefficients of (16) for (m, n) = (3, 5): the Airy function from the
   compatibility equation and the projection of every term of (2) onto sin(m pi x/a) sin(n pi y/b).

The result of 1 is checked against `impact series` at a numeric point, so both sides did the same
derivation. Prints JSON. Run through run.sh."""
import json, sys, time
import sympy as sp

t, s = sp.symbols("t s", real=True)
al, ga, v0, A8, A9 = sp.symbols("alpha gamma v0 a8 a9", real=True)


def canonical(expr):
    expr = sp.powsimp(sp.expand(expr), combine="exp")
    parts = {}
    for term in sp.Add.make_args(sp.expand(expr)):
        coeff, dep = term.as_independent(t, as_Add=False)
        parts[dep] = parts.get(dep, 0) + coeff
    return sp.Add(*[sp.cancel(c) * d for d, c in parts.items() if sp.cancel(c) != 0])


def op_l(g, d):
    integrand = sp.powsimp(sp.expand(sp.exp(d * s) * g.subs(t, s)), combine="exp")
    return sp.exp(-d * t) * sp.integrate(integrand, (s, 0, t), conds="none")


def dint(g):
    inner = sp.integrate(sp.expand(g.subs(t, s)), (s, 0, t), conds="none")
    return sp.integrate(sp.expand(inner.subs(t, s)), (s, 0, t), conds="none")


def adomian(order):
    a = [v0 * t]
    for k in range(order):
        ak = sp.expand(sum(a[i] * a[k - i] for i in range(k + 1)))
        bk = sp.diff(ak, t)
        nxt = -A8 * dint(canonical(op_l(ak, al) - op_l(ak, ga))) - A9 * dint(
            canonical(op_l(bk, al) - op_l(bk, ga)))
        a.append(canonical(nxt))
    return a


def galerkin(m, n):
    x, y, a, b, f, E, D, rho, h, kw, kg, ct, p1, p2 = sp.symbols(
        "x y a b f E D rho h k_w k_g c_t p1 p2", real=True)
    fd, fdd = sp.symbols("fdot fddot", real=True)
    X, Y = sp.sin(m * sp.pi * x / a), sp.sin(n * sp.pi * y / b)
    w = f * X * Y
    L = lambda u, v: (sp.diff(u, x, 2) * sp.diff(v, y, 2) + sp.diff(u, y, 2) * sp.diff(v, x, 2)
                      - 2 * sp.diff(u, x, y) * sp.diff(v, x, y))
    lap = lambda u: sp.diff(u, x, 2) + sp.diff(u, y, 2)
    # Airy function: Delta^2 F = -(E/2) L(w, w), ansatz in cos(2 m pi x/a), cos(2 n pi y/b)
    c1, c2 = sp.symbols("c1 c2")
    F = c1 * sp.cos(2 * m * sp.pi * x / a) + c2 * sp.cos(2 * n * sp.pi * y / b)
    res = sp.expand(sp.simplify(lap(lap(F)) + E / 2 * L(w, w)))
    sol = sp.solve([res.coeff(sp.cos(2 * m * sp.pi * x / a)), res.coeff(sp.cos(2 * n * sp.pi * y / b))],
                   [c1, c2], dict=True)[0]
    F = F.subs(sol) + p1 * y ** 2 / 2 + p2 * x ** 2 / 2
    wt = fd * X * Y
    wtt = fdd * X * Y
    terms = {
        "bending": D * lap(lap(w)), "inertia": rho * h * wtt, "membrane": -L(w, F),
        "winkler": kw * w, "damper": ct * wt, "pasternak": -kg * lap(w),
    }
    norm = a * b / 4
    out = {}
    for name, term in terms.items():
        proj = sp.integrate(sp.integrate(sp.expand(term * X * Y), (x, 0, a)), (y, 0, b))
        out[name] = sp.simplify(proj / norm)
    out["load_sign"] = sp.sin(m * sp.pi / 2) * sp.sin(n * sp.pi / 2)
    return out


def timed(fn, repeats):
    ts, r = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        r = fn()
        ts.append(time.perf_counter() - t0)
    ts.sort()
    return ts[len(ts) // 2], r


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 1
    order = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    sec_series, terms = timed(lambda: adomian(order), repeats)
    point = {al: sp.Rational(-3), ga: sp.Rational(5, 2), v0: 1, A8: 7, A9: sp.Rational(1, 3)}
    partial = sum(terms)
    value = float(sp.N(partial.subs(point).subs(t, sp.Rational(1, 10)), 30))
    sec_gal, g = timed(lambda: galerkin(3, 5), repeats)
    print(json.dumps({"sympy": sp.__version__, "order": order, "series_seconds": sec_series,
                      "series_value_at_t_0.1": value, "galerkin_3_5_seconds": sec_gal,
                      "galerkin_load_sign": int(g["load_sign"]), "repeats": repeats}))


if __name__ == "__main__":
    main()
