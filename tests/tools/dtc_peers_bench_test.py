#!/usr/bin/python3
"""Unit test of the parsing and settling logic of tools/bench/dtc_peers_bench.py
on synthetic force histories whose answers are known in closed form."""
import argparse
import math
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "bench"))
import dtc_peers_bench as b  # noqa: E402


class Settling(unittest.TestCase):
    def test_exponential_approach_settles_where_the_envelope_enters_the_band(self):
        # F_i = R (1 + a exp(-i / tau)); after 3000 iterations the tail mean is R to
        # round-off, so the first index inside the band is ceil(tau ln(a / tol)).
        R, a, tau, tol, n = 30.0, 0.4, 25.0, 1e-3, 3000
        values = [R * (1 + a * math.exp(-i / tau)) for i in range(n)]
        it = list(range(1, n + 1))
        cpu = [0.25 * i for i in it]
        s = b.settling(it, cpu, values, tol)
        expected = math.ceil(tau * math.log(a / tol))
        self.assertEqual(s["index"], expected)
        self.assertEqual(s["iteration"], expected + 1)
        self.assertAlmostEqual(s["cpu"], 0.25 * (expected + 1))
        self.assertAlmostEqual(s["final"], R, places=9)
        self.assertTrue(s["settled"])
        # 1% settles earlier than 0.1%, at its own closed-form index.
        self.assertEqual(b.settling(it, cpu, values, 1e-2)["index"], math.ceil(tau * math.log(a / 1e-2)))

    def test_a_late_excursion_moves_the_settling_point_behind_it(self):
        values = [10.0] * 500
        values[3] = 20.0
        values[321] = 10.02  # 0.2% off: outside 0.1%, inside 1%
        it = list(range(500))
        self.assertEqual(b.settling(it, it, values, 1e-3)["index"], 322)
        self.assertEqual(b.settling(it, it, values, 1e-2)["index"], 4)

    def test_drift_is_not_reported_as_settled(self):
        # Linear drift of 0.01% per iteration: the last-10% window itself spans
        # more than 0.1%, so the end of the run is inside the band only trivially.
        values = [100.0 * (1 + 1e-4 * i) for i in range(1000)]
        s = b.settling(list(range(1000)), list(range(1000)), values, 1e-3)
        self.assertFalse(s["settled"])
        self.assertGreater(s["spread"], 1e-3)

    def test_an_oscillation_passing_through_the_band_at_the_end_is_not_settled(self):
        # 0.5% oscillation with period 50: the window (last 100 = two periods) has
        # mean 1 and spread 0.5%; the last value, 1 + 0.005 sin(-0.126) = 0.99937,
        # happens to be inside the 0.1% band and the one before (0.99876) outside.
        values = [1.0 + 0.005 * math.sin(2 * math.pi * i / 50) for i in range(1000)]
        s = b.settling(list(range(1000)), list(range(1000)), values, 1e-3)
        self.assertEqual(s["index"], 999)
        self.assertAlmostEqual(s["spread"], 0.005, places=4)
        self.assertFalse(s["settled"])

    def test_a_creeping_mean_is_not_settled(self):
        # Drift of 1.5e-5 per iteration: the last window (900..999) lies within 0.075%
        # of its mean 1.0142425 and the history enters the 0.1% band at index 882
        # (1.5e-5 |i - 949.5| <= 1e-3 x 1.0142425), before the window; but the window
        # mean moved by 1.5e-3 / 1.0142 = 0.148% from the window before: not final.
        values = [1.0 + 1.5e-5 * i for i in range(1000)]
        s = b.settling(list(range(1000)), list(range(1000)), values, 1e-3)
        self.assertEqual(s["index"], 882)
        self.assertLess(s["spread"], 1e-3)
        self.assertAlmostEqual(s["drift"], 1.5e-3 / 1.0142425, places=9)
        self.assertFalse(s["settled"])

    def test_last_value_outside_the_band_means_never(self):
        values = [1.0] * 99 + [5.0]
        s = b.settling(list(range(100)), list(range(100)), values, 1e-3)
        self.assertIsNone(s["iteration"])
        self.assertFalse(s["settled"])

    def test_running_mean_averages_out_isolated_spikes(self):
        values = [10.0] * 200
        for i in range(5, 200, 10):
            values[i] = 15.0  # a 50% spike every 10 iterations
        self.assertEqual(b.running_mean([1.0, 2.0, 3.0, 4.0], 2), [1.0, 1.5, 2.5, 3.5])
        it = list(range(200))
        self.assertFalse(b.settling(it, it, values, 1e-2)["settled"])
        sm = b.running_mean(values, 20)  # two spikes in every full window: 10.5 from index 19
        self.assertAlmostEqual(sm[-1], 10.5)
        s = b.settling(it, it, sm, 1e-2)
        self.assertTrue(s["settled"])
        self.assertAlmostEqual(s["final"], 10.5)

    def test_final_value_is_the_mean_of_the_last_tenth(self):
        mean, w = b.final_value(list(range(1, 101)))
        self.assertEqual(w, 10)
        self.assertAlmostEqual(mean, 95.5)

    def test_cpu_per_cell_iteration_excludes_the_start(self):
        it = list(range(1, 101))
        cpu = [5.0 + 0.2 * i for i in it]
        cpu[0] = 0.0  # start-up iteration, skipped
        self.assertAlmostEqual(b.cpu_per_cell_iteration(it, cpu, 1000, 10), 0.2 / 1000)
        with self.assertRaises(ValueError):
            b.cpu_per_cell_iteration(it[:5], cpu[:5], 1000, 10)


class Parsing(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.d = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_peer_outputs(self):
        with open(os.path.join(self.d, "forces.csv"), "w") as f:
            f.write("iter,Fx_total,Fx_pressure,Fx_viscous,Fz_total,clock_s,cpu_s\n")
            for i in range(1, 201):
                fx = -15.0 * (1 + 0.5 * math.exp(-i / 10.0))
                f.write(f"{i},{fx},{fx * 0.4},{fx * 0.6},3.0,{2.0 * i},{0.5 * i}\n")
            f.write("201,-15,-6,-9,3.0,,\n")  # solver killed before its clock line: dropped
        with open(os.path.join(self.d, "timings.txt"), "w") as f:
            f.write("mesh_start 0\nblockMesh 1 s\nmesh_end 101\ncells 127293\nsolve_start 2\n")
        t = b.read_timings(os.path.join(self.d, "timings.txt"))
        self.assertEqual(int(t["cells"]), 127293)
        self.assertEqual(t["mesh_end"] - t["mesh_start"], 101)
        forces = b.read_forces_csv(os.path.join(self.d, "forces.csv"), nproc=2)
        self.assertEqual(len(forces["iter"]), 200)
        self.assertAlmostEqual(forces["cpu"][-1], 2 * 0.5 * 200)  # all ranks
        m = b.peer_metrics(forces, 1000, 1e-3, 10)
        self.assertAlmostEqual(m["R"], 30.0, places=6)  # full hull = -2 Fx
        self.assertAlmostEqual(m["R_pressure"], 12.0, places=6)
        self.assertAlmostEqual(m["cpu_cell_iter"], 1.0 / 1000)
        # 0.5 exp(-i/10) <= 1e-3  <=>  i >= 10 ln 500 = 62.1 -> iteration 63
        self.assertEqual(m["settle"]["iteration"], 63)

    def test_bad_header_is_rejected(self):
        p = os.path.join(self.d, "forces.csv")
        with open(p, "w") as f:
            f.write("time,Fx\n1,2\n")
        with self.assertRaises(ValueError):
            b.read_forces_csv(p)

    def test_run_key_is_independent_of_order(self):
        self.assertEqual(b.run_key("vof", {"NLEV": "4", "NITER": "10"}), "vof-NITER10-NLEV4")
        self.assertEqual(b.run_key("vof", {"NITER": "10", "NLEV": "4"}), "vof-NITER10-NLEV4")

    def test_kelvin_history(self):
        import h5py
        n = 400
        with h5py.File(os.path.join(self.d, "history.h5"), "w") as h:
            h["cpu_time"] = [0.1 * (i + 1) for i in range(n)]
            h["outer_iterations"] = [2.0] * n
            # force on the hull along -x (flow in +x on the body): resistance positive
            h["forces/hull/pressure"] = [[-4.0 * (1 + math.exp(-i / 20.0)), 0.0, 1.0] for i in range(n)]
            h["forces/hull/viscous"] = [[-6.0, 0.1, 0.0] for i in range(n)]
            h["forces/deck/pressure"] = [[0.0, 0.0, 0.0] for i in range(n)]
            h["forces/deck/viscous"] = [[0.0, 0.0, 0.0] for i in range(n)]
        with open(os.path.join(self.d, "kelvin.log"), "w") as f:
            f.write("[info] mesh quality:\ncells 5000  faces 16000 (internal 14000)  points 6000\n")
        with open(os.path.join(self.d, "bench.json"), "w") as f:
            f.write('{"case": "x.yaml", "process_cpu": 45.0}')  # 5 s outside the 40 s time loop
        args = argparse.Namespace(kelvin_patches=None, kelvin_force_factor=2.0, kelvin_cells=None, skip=10,
                                  tol_fine=1e-3, tol_coarse=1e-2)
        m = b.analyse_kelvin(self.d, args)
        self.assertEqual(m["cells"], 5000)
        self.assertAlmostEqual(m["R"], 20.0, places=6)
        self.assertAlmostEqual(m["R_viscous"], 12.0, places=9)
        self.assertAlmostEqual(m["cpu_cell_step"], 0.1 / 5000)
        self.assertAlmostEqual(m["cpu_cell_outer"], 0.05 / 5000)
        # 8 exp(-i/20) <= 20e-3 <=> i >= 20 ln 400 = 119.8 -> index 120, step 121
        self.assertEqual(m["settle_fine"]["iteration"], 121)
        self.assertAlmostEqual(m["settle_fine"]["cpu"], 12.1)
        self.assertAlmostEqual(m["settle_fine"]["cpu_charged"], 17.1)
        args.kelvin_patches = ["keel"]
        with self.assertRaises(SystemExit):
            b.analyse_kelvin(self.d, args)


if __name__ == "__main__":
    unittest.main()
