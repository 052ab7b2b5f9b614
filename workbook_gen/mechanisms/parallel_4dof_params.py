"""Parameters of the spatial 4-DOF parallel mechanism (docs/mechanisms.md, parallel_4dof): names,
defaults, units.

Lengths in m, masses in kg, angles in deg.  The defaults are deliberately asymmetric
(a symmetric layout with P5 on the hinge axis is singular at the home pose).
"""

from __future__ import annotations

from .base import ParamSpec

LEGS = (1, 2, 3, 4)

# leg: (O_i1; gamma_i; l_i1, l_i2; a_i, b_i, c_i; m_i1; u_i1, v_i1, w_i1; m_i2; xi_i)
LEG_DEFAULTS = {
    1: ((0.246, 0.172, 0.0), 0.0, (0.30, 0.46), (0.100, 0.084, 0.0), 1.0,
        (0.140, 0.0, 0.0), 1.2, 0.20),
    2: ((-0.231, 0.276, 0.01), 85.0, (0.26, 0.52), (-0.044, 0.122, 0.01), 1.1,
        (0.120, 0.005, 0.0), 1.1, 0.22),
    3: ((-0.308, -0.144, -0.01), 160.0, (0.30, 0.48), (-0.140, 0.0, 0.0), 0.9,
        (0.160, 0.0, 0.010), 1.3, 0.21),
    4: ((0.172, -0.246, 0.0), 285.0, (0.28, 0.46), (0.084, -0.100, -0.01), 1.0,
        (0.130, -0.004, 0.0), 1.2, 0.19),
}


def _leg(i: int) -> tuple[ParamSpec, ...]:
    (x0, y0, z0), gamma, (l1, l2), (a, b, c), m1, (u, v, w), m2, xi = LEG_DEFAULTS[i]
    P = ParamSpec
    return (
        P(f"x_{i}0", x0, "m", f"leg {i}: hinge centre O_{i}1, x"),
        P(f"y_{i}0", y0, "m", f"leg {i}: hinge centre O_{i}1, y"),
        P(f"z_{i}0", z0, "m", f"leg {i}: hinge centre O_{i}1, z"),
        P(f"gamma_{i}", gamma, "deg",
          f"leg {i}: hinge axis zeta_{i}1 = (cos gamma_{i}, sin gamma_{i}, 0)"),
        P(f"l_{i}1", l1, "m", f"leg {i}: driven link O_{i}1 O_{i}2", positive=True),
        P(f"l_{i}2", l2, "m", f"leg {i}: link O_{i}2 P_{i} (universal to spherical joint)",
          positive=True),
        P(f"a_{i}", a, "m", f"leg {i}: spherical joint P_{i}, platform coordinate a"),
        P(f"b_{i}", b, "m", f"leg {i}: spherical joint P_{i}, platform coordinate b"),
        P(f"c_{i}", c, "m", f"leg {i}: spherical joint P_{i}, platform coordinate c"),
        P(f"m_{i}1", m1, "kg", f"leg {i}: mass of link {i}1"),
        P(f"u_{i}1", u, "m", f"leg {i}: link {i}1's centre of mass along xi_{i}1 (O_{i}1->O_{i}2)"),
        P(f"v_{i}1", v, "m", f"leg {i}: link {i}1's centre of mass along eta_{i}1 "
                            f"= zeta_{i}1 x xi_{i}1"),
        P(f"w_{i}1", w, "m", f"leg {i}: link {i}1's centre of mass along the hinge axis zeta_{i}1"),
        P(f"m_{i}2", m2, "kg", f"leg {i}: mass of link {i}2"),
        P(f"xi_{i}", xi, "m", f"leg {i}: link {i}2's centre of mass on O_{i}2 P_{i}, from O_{i}2"),
    )


def parameters() -> tuple[ParamSpec, ...]:
    P = ParamSpec
    common = (
        P("l_5", 0.5, "m", "leg 5: hinge centre O to the spherical joint P5", positive=True),
        P("m_5", 1.5, "kg", "leg 5: mass"),
        P("l_5c", 0.24, "m", "leg 5: centre of mass from O towards P5 (negative: beyond O)"),
        P("a_5", 0.0, "m", "spherical joint P5, platform coordinate a"),
        P("b_5", 0.0, "m", "spherical joint P5, platform coordinate b"),
        P("c_5", -0.03, "m", "spherical joint P5, platform coordinate c"),
        P("m_P", 2.5, "kg", "moving platform: mass"),
        P("u_P", 0.005, "m", "platform's centre of mass, platform coordinate a"),
        P("v_P", -0.004, "m", "platform's centre of mass, platform coordinate b"),
        P("w_P", 0.010, "m", "platform's centre of mass, platform coordinate c"),
        P("alpha_0", 90.0, "deg", "path: mean leg-5 angle (from x towards z about the hinge y)"),
        P("A_alpha", 12.0, "deg", "path: alpha = alpha_0 + A_alpha sin t"),
        P("A_psi", 10.0, "deg", "path: psi = A_psi sin(t + 45 deg) (rotation about z)"),
        P("A_vartheta", 8.0, "deg", "path: vartheta = A_vartheta cos t (rotation about y)"),
        P("A_phi", 6.0, "deg", "path: phi = A_phi sin 2t (rotation about x)"),
        P("omega_t", 1.0, "rad/s", "rate of the path parameter t"),
    )
    legs = tuple(spec for i in LEGS for spec in _leg(i))
    return common + legs


def counterweight_parameters() -> tuple[ParamSpec, ...]:
    """The counterweights' masses (balance = true); their positions are derived."""
    P = ParamSpec
    return tuple(P(f"m_c{i}", 2.0, "kg", f"counterweight on link {i}1: mass (its position "
                   f"u_c{i}, v_c{i} follows below)", positive=True) for i in LEGS) + (
        P("m_cP", 1.5, "kg", "counterweight on the platform: mass (its position u_cP, v_cP, "
          "w_cP follows below)", positive=True),
        P("m_c5", 8.0, "kg", "counterweight on leg 5: mass (its position s_c5 follows below)",
          positive=True),
    )
