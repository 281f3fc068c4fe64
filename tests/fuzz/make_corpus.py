#!/usr/bin/env python3
"""Writes the fuzzer's seed corpus (tests/fuzz/corpus/) in the byte layout fuzz_harness.h decodes.

Each seed is one meaningful session (a mesh, pins, lambda, operations), so the fuzzer starts from inputs
that reach deep into the solver instead of being refused at the first check. Re-run after changing the
layout in fuzz_harness.h:  python3 tests/fuzz/make_corpus.py
"""
import pathlib
import struct

HERE = pathlib.Path(__file__).resolve().parent

# make_mesh shapes, scales (index into the harness table), operations.
ARBITRARY, OCTAHEDRON, CUBE, GRID, TETRAHEDRA, FAN, NGON_PRISM = range(7)
SCALE = {1.0: 0, 1e6: 1, 1e-6: 2, 1e150: 3, 1e-150: 4, 1e300: 5, 1e-300: 6, 3.0: 7}
SET_STYLES, SET_STYLE, FACE_STYLES, LAMBDA, PINS, ADMM, STEPS, RESET, CHECK, LONG_RUN = range(10)
PRESETS = ["cube", "tetrahedron", "octahedron", "dodecahedron", "icosahedron", "square_pyramid",
           "truncated_pyramid", "triangular_prism", "hexagonal_prism", "plane", "cylinder", "cone",
           "double_cone"]
SPECIAL = {"nan": 234, "inf": 235, "-inf": 236, "1e300": 229, "1e-300": 228, "max": 230}
ADMM_COUNTS = [-1, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 5, 8, 20, 1000, 1001]


class Seed:
    def __init__(self):
        self.b = bytearray()

    def byte(self, v):
        self.b.append(v & 0xFF)
        return self

    def real(self, x):
        """A lattice value x = k/32 in [-4, 4), or a special value by name, or a raw double."""
        if isinstance(x, str):
            return self.byte(SPECIAL[x])
        k = round(x * 32) + 128
        if 0 <= k < 256 and abs((k - 128) / 32 - x) < 1e-12:
            return self.byte(0).byte(k)
        self.byte(240)
        self.b += struct.pack("<d", x)
        return self

    def param(self, x):
        """x = (1 + m/8) * 2^e exactly, with 0 <= m < 8 and -14 <= e <= 13."""
        for e in range(-14, 14):
            for m in range(8):
                if (1 + m / 8) * 2.0 ** e == x:
                    return self.byte(((e + 14) << 3) | m)
        return self.byte(255).real(x)  # anything else: through real()

    def index(self, i):
        return self.byte(0).byte(i & 0xFF).byte((i >> 8) & 0xFF)

    def bad_index(self, which):  # 0: -1, 1: n, 2: n + 1, 3: INT64_MIN, 4: INT64_MAX, ...
        return self.byte(240 + which)

    # --- mesh ---
    def mesh(self, shape, *args, edits=(), scale=1.0, offset=(0, 0, 0)):
        self.byte(shape)
        for a in args:
            self.byte(a)
        self.byte(len(edits))
        for e in edits:
            e(self)
        self.byte(SCALE[scale])
        for x in offset:
            self.real(x)
        return self

    def arbitrary(self, V, F, **kw):
        def body(s):
            s.byte(len(V))
            for v in V:
                for x in v:
                    s.real(x)
            s.byte(len(F))
            for f in F:
                for i in f:
                    s.index(i)
        self.byte(ARBITRARY)
        body(self)
        edits = kw.pop("edits", ())
        self.byte(len(edits))
        for e in edits:
            e(self)
        self.byte(SCALE[kw.pop("scale", 1.0)])
        for x in kw.pop("offset", (0, 0, 0)):
            self.real(x)
        return self

    # --- pins, lambda ---
    def pins(self, idx=(), mode=0, targets=()):
        """mode 0: rest positions; 1: rest + target/8; 2: targets as given."""
        self.byte(132 + len(idx) if idx else 0).byte(mode)  # >= 128 and % 6 == count
        for n, i in enumerate(idx):
            self.index(i)
            if mode:
                for x in targets[n]:
                    self.real(x)
        return self

    def lam(self, x=None):
        return self.byte(0) if x is None else self.byte(255).param(x)

    # --- operations ---
    def ops(self, n):
        return self.byte(n - 1)

    def style(self, preset=None, normals=None, axis=None, rings=None, sigma=None, mu=None,
              axis_contribution=None, quat=None, matrix=None):
        if preset is not None:
            self.byte(0).byte(PRESETS.index(preset))
        elif rings is None:
            self.byte(2).byte(len(normals))
            for n in normals:
                for x in n:
                    self.real(x)
        else:
            normals = normals or []
            self.byte(3).byte(len(normals))
            for n in normals:
                for x in n:
                    self.real(x)
            for x in axis:
                self.real(x)
            self.byte(len(rings))
            for r in rings:
                self.real(4 * r)  # the harness divides by 4
        flags = ((sigma is not None) | (mu is not None) << 1 | (axis_contribution is not None) << 2
                 | (quat is not None) << 3 | (matrix is not None) << 4)
        self.byte(flags)
        for p in (sigma, mu, axis_contribution):
            if p is not None:
                self.param(p)
        if quat is not None:
            for x in quat:
                self.real(x)
        if matrix is not None:
            for x in matrix:
                self.real(x)
        return self

    def set_styles(self, *styles):
        self.byte(SET_STYLES).byte(len(styles))
        for s in styles:
            s(self)
        return self

    def face_styles(self, values, count=None):
        if count is None:
            self.byte(FACE_STYLES).byte(0)
        else:
            self.byte(FACE_STYLES).byte(255).byte(count)
        for v in values:
            self.byte(v)
        return self

    def steps(self, n):
        return self.byte(STEPS).byte(n - 1)

    def admm(self, n):
        return self.byte(ADMM).byte(ADMM_COUNTS.index(n))

    def long_run(self, n):
        """n = 100, 200, ..., 1000 steps, then the read-outs are checked."""
        return self.byte(LONG_RUN).byte(n // 100 - 1)

    # --- after the operations ---
    def keep_pins(self):
        """drag_pins: mode 0 moves each pin target by real()/8; only for seeds without pins."""
        return self.byte(0)

    def cubic(self, lam=None, steps=1, restyle=None, reset=False, back_to_gauss=False):
        """cubic_session: the cubic method (lambda: its default, or lam), `steps` steps (1..64), then
        optionally set_style(0, restyle), reset, and a step of the Gauss method."""
        mode = (lam is not None) | (restyle is not None) << 1 | reset << 2 | back_to_gauss << 3
        self.byte(mode)
        if lam is not None:
            self.param(lam)
        self.byte(steps - 1)
        if restyle is not None:
            restyle(self)
        return self


def seeds():
    out = {}
    out["cube_steps"] = Seed().mesh(CUBE).pins().lam().ops(3).steps(4).byte(CHECK).steps(2)
    out["octahedron_pinned_deform"] = (Seed().mesh(OCTAHEDRON).pins([0, 4], 1, [(0, 0, 2), (1, 1, 0)])
                                       .lam(6.0).ops(2).steps(4).byte(CHECK))
    # GRID bytes: 3 + a % 6 around, 2 + b % 3 across, kind c % 3 (0 flat, 1 tube, 2 Moebius).
    out["moebius_two_styles"] = (Seed().mesh(GRID, 5, 2, 2).pins().lam()  # 8 x 4: 48 faces
                                 .ops(4)
                                 .set_styles(lambda s: s.style("cube"), lambda s: s.style("cylinder", sigma=8.0))
                                 .face_styles([i % 3 for i in range(48)])  # -1, 0, 1 (harness: b % 3 - 1)
                                 .steps(4).byte(CHECK))
    out["tube_cone_admm"] = (Seed().mesh(GRID, 5, 4, 1).pins().lam(2.0).ops(4).admm(3)
                             .set_styles(lambda s: s.style("cone", mu=2.0)).steps(3).byte(CHECK))
    out["tetrahedra_scaled_reset"] = (Seed().mesh(TETRAHEDRA, 5, scale=1e6, offset=(1.5, -2, 0.25))
                                      .pins().lam().ops(5).steps(3).byte(RESET).steps(2).byte(CHECK).steps(1))
    out["tetrahedra_tiny"] = Seed().mesh(TETRAHEDRA, 3, scale=1e-150).pins().lam().ops(2).steps(4).byte(CHECK)
    out["tetrahedra_huge"] = Seed().mesh(TETRAHEDRA, 2, scale=1e150).pins().lam().ops(1).steps(4)
    out["fan_nonmanifold_damaged"] = (
        Seed().mesh(FAN, 3, edits=[lambda s: s.byte(2).index(0).index(1).index(2),   # duplicate face
                                   lambda s: s.byte(3).real(2).real(2).real(2),      # loose vertex
                                   lambda s: s.byte(2).index(1).index(1).index(3)])  # repeated index
        .pins().lam().ops(2).steps(4).byte(CHECK))
    out["cube_zero_area_face"] = (
        Seed().mesh(CUBE, edits=[lambda s: s.byte(0).byte(7).byte(0).real(0),
                                 lambda s: s.byte(0).byte(7).byte(1).real(0),
                                 lambda s: s.byte(0).byte(7).byte(2).real(0)])  # vertex 7 onto vertex 0
        .pins().lam().ops(1).steps(4))
    out["cube_nan_vertex"] = Seed().mesh(CUBE, edits=[lambda s: s.byte(0).byte(3).byte(1).real("nan")]).pins().lam()
    out["cube_bad_index"] = Seed().mesh(CUBE, edits=[lambda s: s.byte(1).byte(5).byte(2).bad_index(1)]).pins().lam()
    out["arbitrary_triangle"] = (Seed().arbitrary([(0, 0, 0), (1, 0, 0.25), (0.25, 1, 0.5)], [(0, 1, 2)])
                                 .pins().lam().ops(2).steps(4).byte(CHECK))
    out["arbitrary_no_faces"] = Seed().arbitrary([(0, 0, 0), (1, 0, 0), (0, 1, 0)], []).pins().lam()
    out["grid_pins_anywhere"] = (Seed().mesh(GRID, 5, 2, 0).pins([0, 5, 9], 2, [(0, 0, 3), (2, 2, 2), (-1, 0, 0)])
                                 .lam().ops(4).steps(2).byte(LAMBDA).param(0.5).byte(PINS).byte(0).byte(0)
                                 .steps(2))
    out["custom_styles"] = (Seed().mesh(OCTAHEDRON).pins().lam().ops(4)
                            .set_styles(lambda s: s.style(normals=[(1, 1, 0), (0, 0, 1), (0, -1, 0)], sigma=16.0,
                                                          quat=(1, 0.5, 0.25, 0)),
                                        lambda s: s.style(normals=[(0, 0, 1)], axis=(1, 0, 1), rings=[0.25, -0.5],
                                                          axis_contribution=0.25))
                            .face_styles([1, 2, 0, 1, 2, 0, 1, 2])
                            .steps(4).byte(CHECK))
    out["bad_style_params"] = (Seed().mesh(CUBE).pins().lam().ops(3)
                               .set_styles(lambda s: s.style("cube", matrix=[2, 0, 0, 0, 1, 0, 0, 0, 1]),
                                           lambda s: s.style(normals=[]))
                               .byte(SET_STYLE).byte(5).style("plane", sigma=1e-300)
                               .steps(2))
    out["extreme_params"] = (Seed().mesh(GRID, 4, 3, 1).pins().lam(8192.0).ops(4)
                             .set_styles(lambda s: s.style("double_cone", sigma=8192.0, mu=8192.0))
                             .admm(20).steps(2).byte(CHECK))
    # Blender's 16-sided cylinder with 8 cuts: 144-gon caps fanned from a corner (zero-area and long thin
    # triangles, float coordinates); a live run left going for 1000 steps at lambda 1, 4 and 20.
    # NGON_PRISM bytes: 3 + a % 14 sides, b % 9 cuts, height 0.25 + c % 8 / 4.
    for lam in (1.0, 4.0, 20.0):
        out[f"ngon_cylinder_lambda{lam:g}_long_run"] = (Seed().mesh(NGON_PRISM, 13, 8, 7).pins().lam(lam)
                                                         .ops(1).long_run(1000))
    out["ngon_prism_4_cuts_pinned"] = (Seed().mesh(NGON_PRISM, 9, 4, 3).pins([0, 60], 1, [(0, 0, 1), (1, 0, 0)])
                                       .lam().ops(3).steps(4).byte(CHECK).long_run(300))
    # Slivers next to good triangles: a square's diagonal split at a point 2^-20 off it, so one triangle
    # has an angle of ~180 degrees between good ones; a tent on top closes it. Then a long run.
    eps = 2.0 ** -20
    bottom = [(0, 1, 6), (6, 1, 7), (7, 1, 2), (0, 6, 3), (6, 4, 3), (4, 7, 3), (7, 2, 3), (6, 7, 4)]
    out["slivers_next_to_good_triangles"] = (
        Seed().arbitrary([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5 + eps, 0), (0.5, 0.5, 1),
                          (0.25, 0.25, 0), (0.75, 0.75, 0)],
                         [(a, c, b) for a, b, c in bottom] + [(0, 1, 5), (1, 2, 5), (2, 3, 5), (3, 0, 5)])
        .pins().lam(20.0).ops(1).long_run(1000))
    # The cubic method after a Gauss run: slivers, a turned style, a reset, and back; its largest lambda.
    out["cubic_ngon_cylinder_restyled"] = (
        Seed().mesh(NGON_PRISM, 13, 8, 7).pins().lam().ops(1).steps(2).keep_pins()
        .cubic(0.5, 64, restyle=lambda s: s.style("cube", mu=2.0, quat=(0.9, 0.1, 0.3, 0.2)), reset=True,
               back_to_gauss=True))
    out["cubic_grid_lambda_64"] = (Seed().mesh(GRID, 5, 4, 1).pins().lam().ops(1).steps(1).keep_pins()
                                   .cubic(64.0, 64))
    out["empty"] = Seed()
    return out


def main():
    corpus = HERE / "corpus"
    corpus.mkdir(exist_ok=True)
    for name, seed in seeds().items():
        (corpus / name).write_bytes(bytes(seed.b))
    print(f"wrote {len(seeds())} seeds to {corpus}")


if __name__ == "__main__":
    main()
