#!/usr/bin/env python3
"""MJCF of the chains of models/planar_chain.eom and models/universal_chain.eom, for MuJoCo.

    mujoco_chains.py planar|universal N [-o FILE]

Same bodies, joints, inertias and gravity as the .eom models with their default parameters:
explicit <inertial> (mass, centre, diaginertia in the body frame, no geoms at all, so nothing
collides and nothing contributes inertia), contacts disabled, no damping/armature/springs,
integrator RK4 with timestep 1 ms.

planar:    frames b_i = rotate(b_{i-1}, 3, q_i), i.e. C_{b_i b_{i-1}} = C3(q_i); a positive q_i
           turns b_i counterclockwise about a.3 = MuJoCo hinge about +z with qpos = q_i.
           Rod along -b_i.2, gravity -g a.2 (MuJoCo gravity "0 -g 0").
universal: C_{j_i b_{i-1}} = C1(alpha_i), C_{b_i j_i} = C2(beta_i); MuJoCo composes the joints
           of one body in order, each about its axis in the frame already rotated by the ones
           before (xquat = xquat * axisangle(axis, qpos)), so hinge x then hinge y gives
           qpos = (alpha_i, beta_i). Rod along -b_i.3, gravity -g a.3.
Verified numerically in mujoco_bench.cpp: M, F = -qfrc_bias and qacc agree to ~1e-15, and,
since those cannot see a mirrored convention (axis -x, or y before x, gives the same dynamics
for these axisymmetric rods), body orientations xmat = C_{a b_i} and the tip position and
velocity agree with the model to ~1e-16 (a flipped axis or swapped order fails that by O(1)).
"""
import argparse
import sys


def r(x):
    # shortest repr that round-trips: MuJoCo parses exactly the double Python holds
    return repr(float(x))


def chain(name, body, n, gravity, offset, joints, inertial):
    """n nested bodies named body1..bodyn, each hung at `offset` (MJCF vector text) from the
    one above, with the hinges `joints` [(joint name prefix, axis)] and `inertial` attributes"""
    out = [f'<mujoco model="{name}_{n}">',
           '  <compiler angle="radian" inertiafromgeom="false"/>',
           f'  <option timestep="0.001" integrator="RK4" gravity="{gravity}">',
           '    <flag contact="disable"/>',
           '  </option>',
           '  <worldbody>']
    ind = '    '
    for i in range(1, n + 1):
        pos = '0 0 0' if i == 1 else offset
        out.append(f'{ind}<body name="{body}{i}" pos="{pos}">')
        for joint, axis in joints:
            out.append(f'{ind}  <joint name="{joint}{i}" type="hinge" axis="{axis}" pos="0 0 0"/>')
        out.append(f'{ind}  <inertial {inertial}/>')
        ind += '  '
    for i in range(n, 0, -1):
        ind = ind[:-2]
        out.append(f'{ind}</body>')
    out += ['  </worldbody>', '</mujoco>']
    return '\n'.join(out) + '\n'


def planar(n, m=0.5, l=0.3, rd=0.01, g=9.81):
    # same association as the generated code: 1/12 m (l^2 + 3 rd^2)
    ia = 0.08333333333333333 * m * (l * l + rd * rd * 3)
    ib = 0.5 * m * rd * rd
    return chain('planar_chain', 'rod', n, f'0 {r(-g)} 0', f'0 {r(-l)} 0', [('q', '0 0 1')],
                 f'pos="0 {r(-0.5 * l)} 0" mass="{r(m)}" diaginertia="{r(ia)} {r(ib)} {r(ia)}"')


def universal(n, m=1.0, l=0.4, rd=0.02, g=9.81):
    ia = 0.08333333333333333 * m * (l * l + rd * rd * 3)
    ic = 0.5 * m * rd * rd
    return chain('universal_chain', 'link', n, f'0 0 {r(-g)}', f'0 0 {r(-l)}', [('alpha', '1 0 0'), ('beta', '0 1 0')],
                 f'pos="0 0 {r(-0.5 * l)}" mass="{r(m)}" diaginertia="{r(ia)} {r(ia)} {r(ic)}"')


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('chain', choices=['planar', 'universal'])
    ap.add_argument('n', type=int)
    ap.add_argument('-o', '--output')
    a = ap.parse_args()
    if a.n < 1:
        sys.exit('n must be >= 1')
    xml = planar(a.n) if a.chain == 'planar' else universal(a.n)
    if a.output:
        with open(a.output, 'w') as f:
            f.write(xml)
    else:
        sys.stdout.write(xml)


if __name__ == '__main__':
    main()
