#!/usr/bin/env python3
"""Model files of the scaling benchmark (bench/scaling.sh): one family, one size, on stdout.

    python3 bench/scaling/models.py FAMILY N > model.eom

Every statement is written out (no `for` loops), so a file of size N is what a user would
write by hand, and the time the benchmark measures includes reading it. The families:

  chained        N derived parameters a1..aN, each using the one before it twice
                 (a{i} = a{i-1}*(1 + sin(a{i-1}/L)) + L): a tree of 2^N nodes written out,
                 N short definitions as symbols (issue 28); a pendulum of length aN.
  nested_points  N points, each placed from the position of the one before inside sin and cos;
                 a particle at the last, all on one pendulum angle q. Written out, the last
                 position is a tree that doubles with every point.
  nested_sin     a particle at l*sin(sin(...sin(q)...))*a.1, N sines deep. The language nests
                 an expression at most 100 levels, so the nest is cut into pieces of at most
                 95 sines, each a helper point whose a.1 component the next piece continues
                 (dot(position(s{k-1}), a.1)/l): one expression up to N = 95, the same
                 function of q written through points beyond.
  cosine_sum     a pendulum with the potential k*(cos(q) + cos(2*q)/2 + ... + cos(N*q)/N),
                 one expression of N terms.
  parameter_sum  N parameters k1..kN and a derived parameter L = k1 + ... + kN, one expression
                 of N terms; a pendulum of length L.

Every model has units and passes `eomgen check`. The output depends on FAMILY and N only.
"""
import sys

# the language's limit is 100 levels of nesting; a piece of the nest also sits inside
# l*...*a.1, dot(...) and position(...)
SINES_PER_PIECE = 95


def chained(n):
    lines = [
        'model chained "chained derived parameters"',
        "parameter L = 0.5 [m]",
        "parameter g = 9.81 [m/s^2]",
        "parameter m = 1 [kg]",
        "parameter a0 = L [m]",
    ]
    lines += [f"parameter a{i} = a{i - 1}*(1 + sin(a{i - 1}/L)) + L [m]" for i in range(1, n + 1)]
    lines += [
        "coordinate q",
        "frame b = rotate(a, 3, q)",
        f"point p = w - a{n}*b.2",
        "particle bob(mass = m, at = p)",
        "gravity = -g*a.2",
    ]
    return lines


def nested_points(n):
    lines = [
        'model nested_points "points defined from the position of the point before"',
        "parameter l = 0.5 [m]",
        "parameter g = 9.81 [m/s^2]",
        "parameter m = 1 [kg]",
        "coordinate q",
        "frame b = rotate(a, 3, q)",
        "point p0 = w - l*b.2",
    ]
    for i in range(1, n + 1):
        prev = f"p{i - 1}"
        lines.append(f"point p{i} = {prev} + l*sin(dot(position({prev}), a.2)/l)*a.1"
                     f" + l*cos(dot(position({prev}), a.1)/l)*a.2")
    lines += [f"particle bob(mass = m, at = p{n})", "gravity = -g*a.2"]
    return lines


def nested_sin(n):
    lines = [
        'model nested_sin "a particle at l*sin(sin(...sin(q)...))*a.1"',
        "parameter l = 0.5 [m]",
        "parameter g = 9.81 [m/s^2]",
        "parameter m = 1 [kg]",
        "coordinate q",
    ]
    inner, done, piece = "q", 0, 0
    while done < n:
        depth = min(SINES_PER_PIECE, n - done)
        expression = "sin(" * depth + inner + ")" * depth
        done += depth
        piece += 1
        name = "p" if done == n else f"s{piece}"
        lines.append(f"point {name} = w + l*{expression}*a.1")
        inner = f"dot(position({name}), a.1)/l"
    lines += ["particle bob(mass = m, at = p)", "gravity = -g*a.1"]
    return lines


def cosine_sum(n):
    terms = ["cos(q)"] + [f"cos({k}*q)/{k}" for k in range(2, n + 1)]
    return [
        'model cosine_sum "a pendulum with a potential of cosine terms"',
        "parameter l = 0.5 [m]",
        "parameter m = 1 [kg]",
        "parameter k = 0.1 [J]",
        "coordinate q",
        "frame b = rotate(a, 3, q)",
        "point p = w + l*b.1",
        "particle bob(mass = m, at = p)",
        f"potential ripple = k*({' + '.join(terms)})",
    ]


def parameter_sum(n):
    lines = [
        'model parameter_sum "a derived parameter that sums parameters"',
        "parameter g = 9.81 [m/s^2]",
        "parameter m = 1 [kg]",
    ]
    lines += [f"parameter k{i} = 0.01 [m]" for i in range(1, n + 1)]
    lines += [
        f"parameter L = {' + '.join(f'k{i}' for i in range(1, n + 1))} [m]",
        "coordinate q",
        "frame b = rotate(a, 3, q)",
        "point p = w - L*b.2",
        "particle bob(mass = m, at = p)",
        "gravity = -g*a.2",
    ]
    return lines


FAMILIES = {f.__name__: f for f in (chained, nested_points, nested_sin, cosine_sum, parameter_sum)}


def main(argv):
    if len(argv) != 3 or argv[1] not in FAMILIES or not argv[2].isdigit() or int(argv[2]) < 1:
        sys.stderr.write(f"usage: {argv[0]} {{{','.join(FAMILIES)}}} N   (N >= 1)\n")
        return 2
    family, n = argv[1], int(argv[2])
    sys.stdout.write(f"# bench/scaling/models.py {family} {n}\n")
    sys.stdout.write("\n".join(FAMILIES[family](n)) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
