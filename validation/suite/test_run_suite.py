#!/usr/bin/env python3
"""Checks of run_suite.py's refinement levels on the committed scenes (ctest RunSuite.*): which
knots each level's scene copy gets. The suite's convergence checks are only as good as these
meshes, and a level that silently kept the committed mesh would report a change of zero. Also
the report's Richardson estimate of the finest level's error.

Usage: /usr/bin/python3 validation/suite/test_run_suite.py (unittest; no isomuscle run)
"""
import os
import re
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_suite  # noqa: E402


def example(name):
    return next(e for e in run_suite.EXAMPLES if e["name"] == name)


def mesh_of(path):
    """(knot insertion, {direction: explicit knots}) of a written scene."""
    with open(path) as f:
        text = f.read()
    k = [int(x) for x in re.search(r"^knot_insertion = \[([^\]]*)\]", text, re.M).group(1)
         .split(",")]
    knots = {}
    line = re.search(r"^knots = \{([^}]*)\}", text, re.M)
    for name, values in re.findall(r"([uvw]) = \[([^\]]*)\]", line.group(1) if line else ""):
        knots[name] = [float(x) for x in values.split(",")]
    return k, knots


def spans(knots):
    points = [0.0] + knots + [1.0]
    return [b - a for a, b in zip(points, points[1:])]


class SceneVariants(unittest.TestCase):
    def setUp(self):
        self.temporary = tempfile.TemporaryDirectory()
        self.folder = self.temporary.name

    def tearDown(self):
        self.temporary.cleanup()

    def variant(self, name, level, directions, tag=""):
        ex = example(name)
        path, _ = run_suite.scene_variant(ex["scenes"][next(iter(ex["scenes"]))], level, directions,
                                          "", self.folder, ex.get("base_spans"), tag)
        return path, mesh_of(path)

    def test_dao_levels_halve_every_span_along_the_graded_ones_too(self):
        _, (k0, knots0) = self.variant("dao", 0, "v")
        _, (k1, knots1) = self.variant("dao", 1, "v")
        _, (_, knots2) = self.variant("dao", 2, "v")
        # Level 0 is the committed mesh: 12 uniform spans (3 of the centreline, each split 4
        # times) merged with the six graded knots, 18 spans, the first 1/768.
        self.assertEqual(k0, [3, 0, 3])
        self.assertEqual(len(spans(knots0["v"])), 18)
        self.assertAlmostEqual(spans(knots0["v"])[0], 1.0 / 768, delta=1e-15)
        self.assertAlmostEqual(sum(spans(knots0["v"])), 1.0, delta=1e-14)
        for coarse, fine in [(knots0["v"], knots1["v"]), (knots1["v"], knots2["v"])]:
            s, f = spans(coarse), spans(fine)
            self.assertEqual(len(f), 2 * len(s))
            for i, h in enumerate(s):
                self.assertAlmostEqual(f[2 * i], h / 2, delta=1e-15)
                self.assertAlmostEqual(f[2 * i + 1], h / 2, delta=1e-15)
        self.assertEqual(k1, [3, 0, 3])  # around and radial as committed

    def test_dao_one_direction_sequences_refine_that_direction_alone(self):
        committed = mesh_of(os.path.join(run_suite.EXAMPLES_DIR, "dao", "contract.toml"))
        self.assertEqual(run_suite.sequences(example("dao")),
                         [("v", ""), ("u", "-u"), ("w", "-w")])
        for level, direction, expected in [(1, "u", [7, 3, 3]), (2, "u", [15, 3, 3]),
                                           (1, "w", [3, 3, 7]), (2, "w", [3, 3, 15])]:
            tag = "-" + direction
            path, (k, knots) = self.variant("dao", level, direction, tag)
            self.assertEqual(k, expected)
            self.assertEqual(knots, committed[1])  # the graded knots along, untouched
            self.assertTrue(path.endswith("dao_contract-L%d%s.toml" % (level, tag)))

    def test_cone_grading_is_halved_from_one_span(self):
        _, (k1, knots1) = self.variant("cone", 1, "v")
        committed = mesh_of(os.path.join(run_suite.EXAMPLES_DIR, "cone", "contract.toml"))[1]["v"]
        grid = sorted(set([j / 4.0 for j in range(1, 4)] + committed))
        self.assertEqual(k1, [0, 0, 3])
        self.assertEqual(len(spans(knots1["v"])), 2 * len(spans(grid)))
        self.assertAlmostEqual(spans(knots1["v"])[0], committed[0] / 2, delta=1e-15)

    def test_uniform_directions_double_their_insertion(self):
        # The torus refines all three directions together: 4 x 8 x 2 spans, then 16 x 32 x 8.
        self.assertEqual(run_suite.sequences(example("torus")), [("uvw", "")])
        _, (k, knots) = self.variant("torus", 2, "uvw")
        self.assertEqual(k, [7, 31, 7])
        self.assertEqual(knots, {})

    def test_half_torus_refines_around_alone_too(self):
        self.assertEqual(run_suite.sequences(example("half_torus")), [("vw", ""), ("u", "-u")])
        for level, expected in [(1, [1, 3, 1]), (2, [3, 3, 1])]:
            path, (k, _) = self.variant("half_torus", level, "u", "-u")
            self.assertEqual(k, expected)  # 8, then 16 around; along and radial as committed
            self.assertTrue(path.endswith("half_torus_contract-L%d-u.toml" % level))


class Richardson(unittest.TestCase):
    """The finest level's error estimate of the report (run_suite.richardson)."""

    def test_first_order_sequence_extrapolates_to_its_limit(self):
        limit, c = 0.9, 0.04
        values = [limit + c, limit + c / 2, limit + c / 4]
        e = run_suite.richardson(values)
        self.assertAlmostEqual(e["ratio"], 0.5, delta=1e-12)
        self.assertAlmostEqual(e["order"], 1.0, delta=1e-12)
        self.assertAlmostEqual(e["limit"], limit, delta=1e-12)
        self.assertAlmostEqual(e["error"], (c / 4) / (limit + c / 4), delta=1e-12)

    def test_second_order_sequence_has_order_two(self):
        values = [2.0 - 1.0, 2.0 - 0.25, 2.0 - 0.0625, 2.0 - 0.015625]
        e = run_suite.richardson(values)  # the last three
        self.assertAlmostEqual(e["ratio"], 0.25, delta=1e-12)
        self.assertAlmostEqual(e["order"], 2.0, delta=1e-12)
        self.assertAlmostEqual(e["limit"], 2.0, delta=1e-12)

    def test_dao_radial_levels_of_the_eleventh_session(self):
        # The NURBS end y (mm) at 4 / 8 / 16 radial spans: the suite README's extrapolated
        # +0.907 mm, 1.3 % from the 16-span run.
        e = run_suite.richardson([0.9530, 0.9299, 0.9184])
        self.assertAlmostEqual(e["limit"], 0.907, delta=5e-4)
        self.assertAlmostEqual(e["error"], 0.0125, delta=5e-4)

    def test_no_estimate_without_a_shrinking_monotone_change(self):
        oscillating = run_suite.richardson([1.0, 1.1, 1.05])
        self.assertLess(oscillating["ratio"], 0.0)
        self.assertNotIn("error", oscillating)
        growing = run_suite.richardson([1.0, 1.1, 1.3])
        self.assertGreater(growing["ratio"], 1.0)
        self.assertNotIn("error", growing)
        self.assertEqual(run_suite.estimate_text([1.0, 1.1, 1.3]), "")
        self.assertIsNone(run_suite.richardson([1.0, 1.1]))
        self.assertIsNone(run_suite.richardson([1.0, float("nan"), 1.1]))
        self.assertIsNone(run_suite.richardson([1.0, 1.0, 1.0]))
        self.assertEqual(run_suite.richardson_text([1.0, 1.0, 1.0]), "-")

    def test_report_texts(self):
        self.assertEqual(run_suite.richardson_text([1.04, 1.02, 1.01]), "r 0.50, p 1.0, 0.99 %")
        self.assertEqual(run_suite.estimate_text([1.04, 1.02, 1.01]),
                         "; est. error of the finest 0.99 % (r 0.50)")


if __name__ == "__main__":
    unittest.main()
