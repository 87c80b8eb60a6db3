"""The Python module `quadra` (python/quadra_module.cpp), run by CTest
(tests/CMakeLists.txt, test `Python`) as

    test_quadra.py QUADRA_CLI READ_REFERENCE GLB ANIMATED_GLB

with PYTHONPATH=build/python. Exits non-zero when a test fails, errors, or
when no test ran at all (Python 3.11's unittest exits 0 after "Ran 0 tests").
"""
import os
import subprocess
import sys
import tempfile
import threading
import unittest

import numpy as np

import quadra

CLI, READ_REFERENCE, GLB, ANIMATED = (sys.argv[1:5] if len(sys.argv) >= 5 else (None,) * 4)
# The programs this test runs carry their own sanitizer runtime where they
# have one (clang links it into each executable): the one preloaded into
# this interpreter for the module (tests/CMakeLists.txt) must not reach them.
CHILD_ENV = {name: value for name, value in os.environ.items() if name != "LD_PRELOAD"}


def run_program(args, **options):
    return subprocess.run(args, env=CHILD_ENV, **options)

# The C API test's quad (tests/c_api/test_c_api.c): x, y in [-0.5, 0.5] at
# z = 0, seen orthographically from z = 1 over [-1, 1]^2, near 0.5, far 2.
QUAD_POSITIONS = np.array([[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]],
                          dtype=np.float32)
QUAD_INDICES = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
# v = 0 is the texture's top row: the quad's top edge (y = 0.5) reads it.
QUAD_UVS = np.array([[0, 1], [1, 1], [1, 0], [0, 0]], dtype=np.float32)
BASE = np.array([0.25, 0.5, 0.75, 1.0], dtype=np.float32)


def translation(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def quad_scene(indices=QUAD_INDICES, transform=None, texture=None):
    scene = quadra.Scene()
    mesh = scene.add_mesh(QUAD_POSITIONS, indices, uvs=QUAD_UVS)
    material = scene.add_material(base_color=tuple(BASE) if texture is None else (1, 1, 1, 1),
                                  texture=texture and texture(scene))
    scene.add_instance(mesh, material, transform)
    scene.set_camera(quadra.Camera(projection="orthographic", ymag=1.0, znear=0.5, zfar=2.0,
                                   world=translation(0, 0, 1)))
    return scene


class RenderFromNumpy(unittest.TestCase):
    def setUp(self):
        self.renderer = quadra.Renderer(threads=2)

    def test_quad_pixels_and_depths_are_the_analytic_ones(self):
        # 40x40 pixels over [-1, 1]^2: centres -0.975 + 0.05 i; the quad holds
        # pixels 10..29 each way, depth (1 - 0.5) / (2 - 0.5) = 1/3 there.
        out = self.renderer.render(quad_scene(), width=40, height=40)
        self.assertEqual(out.color.shape, (40, 40, 4))
        self.assertEqual(out.color.dtype, np.float32)
        self.assertEqual(out.depth.shape, (40, 40))
        expected = np.zeros((40, 40, 4), np.float32)
        expected[10:30, 10:30] = BASE
        np.testing.assert_array_equal(out.color, expected)
        inside = np.zeros((40, 40), bool)
        inside[10:30, 10:30] = True
        np.testing.assert_allclose(out.depth[inside], 1 / 3, atol=1e-6, rtol=0)
        np.testing.assert_array_equal(out.depth[~inside], 1.0)

    def test_uint16_indices_draw_what_uint32_ones_do(self):
        a = self.renderer.render(quad_scene(QUAD_INDICES), width=24, height=24)
        b = self.renderer.render(quad_scene(QUAD_INDICES.astype(np.uint16)), width=24, height=24)
        np.testing.assert_array_equal(a.color, b.color)
        self.assertGreater(int((a.color[..., 3] > 0).sum()), 0)

    def test_transform_is_a_maths_matrix_with_translation_in_the_last_column(self):
        # Moved right by 0.25 = 5 pixels and up by 0.5 = 10 pixels (row 0 the top).
        out = self.renderer.render(quad_scene(transform=translation(0.25, 0.5, 0)),
                                   width=40, height=40)
        expected = np.zeros((40, 40, 4), np.float32)
        expected[0:20, 15:35] = BASE
        np.testing.assert_array_equal(out.color, expected)

    def test_textures_from_each_dtype_are_read_texel_for_texel(self):
        # A 2x2 texture with nearest filtering: each texel fills a quarter of
        # the quad (pixels 4..11 of 16), row 0 at the top.
        texels = np.array([[[1, 0, 0, 1], [0, 1, 0, 1]], [[0, 0, 1, 1], [1, 1, 0.5, 1]]])
        for dtype in (np.float32, np.float16):
            with self.subTest(dtype=dtype.__name__):
                arr = texels.astype(dtype)
                scene = quad_scene(texture=lambda s: s.add_texture(arr, filter="nearest"))
                out = self.renderer.render(scene, width=16, height=16)
                block = np.repeat(np.repeat(texels.astype(np.float32), 4, 0), 4, 1)
                np.testing.assert_array_equal(out.color[4:12, 4:12], block)
        # UNORM8 (srgb=False): 0.5 -> code 127, read back as 127/255 linear to
        # float rounding (the engine multiplies by 1/255, one ulp from 127/255).
        unorm = (texels * 255).astype(np.uint8)
        scene = quad_scene(texture=lambda s: s.add_texture(unorm, srgb=False, filter="nearest"))
        out = self.renderer.render(scene, width=16, height=16)
        self.assertAlmostEqual(float(out.color[10, 10, 2]), 127 / 255, delta=2 ** -24)
        self.assertEqual(float(out.color[10, 10, 0]), 1.0)

    def test_out_reuses_the_arrays_of_an_earlier_render_of_that_size(self):
        first = self.renderer.render(quad_scene(), width=40, height=40)
        fresh = self.renderer.render(quad_scene(transform=translation(0.25, 0, 0)), width=40,
                                     height=40)
        again = self.renderer.render(quad_scene(transform=translation(0.25, 0, 0)), width=40,
                                     height=40, out=first)
        self.assertIs(again.color, first.color)
        self.assertIs(again.depth, first.depth)
        np.testing.assert_array_equal(again.color, fresh.color)
        np.testing.assert_array_equal(again.depth, fresh.depth)
        other = self.renderer.render(quad_scene(), width=20, height=40, out=first)
        self.assertIsNot(other.color, first.color)
        self.assertEqual(other.color.shape, (40, 20, 4))

    def test_aovs_of_the_quad_are_its_analytic_values(self):
        # The quad of the test above: N = (0, 0, 1), P = (x, y, 0) and uv
        # linear across it at the pixel centres, its ids and full coverage;
        # off it the clear values (docs/cli.md "AOVs").
        out = self.renderer.render(quad_scene(), width=40, height=40,
                                   aovs=("N", "P", "uv", "id", "mask"))
        inside = np.zeros((40, 40), bool)
        inside[10:30, 10:30] = True
        centres = -0.975 + 0.05 * np.arange(40)
        x, y = np.meshgrid(centres, -centres)
        self.assertEqual(out.normal.shape, (40, 40, 3))
        self.assertEqual(out.uv.shape, (40, 40, 2))
        self.assertEqual(out.primitive_id.dtype, np.uint32)
        np.testing.assert_array_equal(out.normal[inside], [[0, 0, 1]] * 400)
        np.testing.assert_allclose(out.position[inside], np.stack([x, y, 0 * x], -1)[inside],
                                   atol=1e-6, rtol=0)
        np.testing.assert_allclose(out.uv[inside], np.stack([x + 0.5, 0.5 - y], -1)[inside],
                                   atol=1e-6, rtol=0)
        np.testing.assert_array_equal(out.mask, inside.astype(np.float32))
        np.testing.assert_array_equal(out.node_id[inside], 0)
        np.testing.assert_array_equal(out.material_id[inside], 0)
        # triangle 0 is (0, 1, 2), below the diagonal x = y; the fill rule
        # gives the centres on the diagonal to one of the two
        off_diagonal = inside & (np.abs(x - y) > 0.01)
        np.testing.assert_array_equal(out.primitive_id[off_diagonal],
                                      (x < y)[off_diagonal].astype(np.uint32))
        for ids in (out.primitive_id, out.node_id, out.material_id):
            np.testing.assert_array_equal(ids[~inside], 0xFFFFFFFF)
        for floats in (out.normal, out.position, out.uv):
            np.testing.assert_array_equal(floats[~inside], 0)

    def test_aovs_not_asked_are_none_and_out_reuses_their_arrays(self):
        first = self.renderer.render(quad_scene(), width=40, height=40, aovs=["N", "id"])
        self.assertIsNone(first.position)
        self.assertIsNone(first.mask)
        again = self.renderer.render(quad_scene(transform=translation(0.25, 0, 0)), width=40,
                                     height=40, aovs=["N", "id"], out=first)
        self.assertIs(again.normal, first.normal)
        self.assertIs(again.node_id, first.node_id)
        fresh = self.renderer.render(quad_scene(transform=translation(0.25, 0, 0)), width=40,
                                     height=40, aovs=["N", "id"])
        np.testing.assert_array_equal(again.normal, fresh.normal)
        np.testing.assert_array_equal(again.primitive_id, fresh.primitive_id)

    def test_depth_can_be_left_out(self):
        out = self.renderer.render(quad_scene(), width=8, height=8, depth=False)
        self.assertIsNone(out.depth)

    def test_concurrent_renders_from_python_threads_agree(self):
        scene = quad_scene()
        results = [None] * 4
        renderers = [quadra.Renderer(threads=1) for _ in results]

        def work(i):
            results[i] = renderers[i].render(scene, width=64, height=48).color

        threads = [threading.Thread(target=work, args=(i,)) for i in range(len(results))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for r in results[1:]:
            np.testing.assert_array_equal(r, results[0])

    def test_changing_a_scene_while_another_thread_renders_it_is_refused(self):
        # render releases the GIL; a change meanwhile would be a data race
        # in the engine, so the module refuses it with the API's error type.
        scene = quad_scene()
        renderer = quadra.Renderer(threads=1)
        done = threading.Event()

        def work():
            for _ in range(5):
                renderer.render(scene, width=1024, height=1024, samples=8)
            done.set()

        thread = threading.Thread(target=work)
        thread.start()
        refused, changed = 0, 0
        while not done.is_set():
            try:
                scene.add_material()
                changed += 1
            except quadra.Error as error:
                self.assertEqual(str(error), "scene: changed while a render reads it")
                refused += 1
        thread.join()
        self.assertGreater(refused, 0)
        scene.add_material()  # and allowed again once no render reads it


class RenderGltfEqualsTheCli(unittest.TestCase):
    def test_version_is_the_clis(self):
        # The module's is the library's (quadra::version()), the CLI's its
        # headers' QUADRA_VERSION_STRING: both project(VERSION), which the
        # wheel of `pip install .` carries too (python/quadra_build.py).
        if CLI is None:
            self.skipTest("run by CTest with the CLI's path")
        printed = run_program([CLI, "--version"], check=True, capture_output=True, text=True)
        self.assertEqual(printed.stdout, f"quadra {quadra.__version__}\n")
        self.assertRegex(quadra.__version__, r"^\d+\.\d+\.\d+$")

    def test_render_equals_the_cli_exr_bit_for_bit(self):
        # The judge is the InstallAndFindPackage test's: read_reference reads
        # the CLI's EXR (R, G, B, A, Z floats) with OpenEXR and compares every
        # value's bits with the raw pixels and depths (and needs > 1/4 covered).
        if CLI is None:
            self.skipTest("run by CTest with the CLI and read_reference paths")
        with tempfile.TemporaryDirectory() as work:
            exr = os.path.join(work, "cli.exr")
            run_program([CLI, "render", GLB, "--shading", "unlit", "--width", "96", "--height",
                         "72", "--threads", "2", "--out", exr],
                        check=True, stdout=subprocess.DEVNULL)
            out = quadra.Renderer(threads=2).render(quadra.load(GLB), width=96, height=72)
            raw = os.path.join(work, "python.raw")
            with open(raw, "wb") as f:
                f.write(out.color.tobytes() + out.depth.tobytes())
            judged = run_program([READ_REFERENCE, exr, raw], capture_output=True, text=True)
            self.assertEqual(judged.returncode, 0, judged.stdout + judged.stderr)
            # The judge can fail: one value off by one ulp is caught.
            out.color[36, 48, 0] = np.nextafter(out.color[36, 48, 0], np.float32(2))
            with open(raw, "wb") as f:
                f.write(out.color.tobytes() + out.depth.tobytes())
            judged = run_program([READ_REFERENCE, exr, raw], capture_output=True, text=True)
            self.assertNotEqual(judged.returncode, 0, judged.stdout)

    def test_aovs_equal_the_cli_exr_channels_bit_for_bit(self):
        # The CLI's --aov channels, read with OpenEXR by read_reference
        # --channels as stored (FLOAT, or UINT for the ids), against the
        # arrays' bytes.
        if CLI is None:
            self.skipTest("run by CTest with the CLI and read_reference paths")
        with tempfile.TemporaryDirectory() as work:
            exr = os.path.join(work, "cli.exr")
            run_program([CLI, "render", GLB, "--shading", "unlit", "--width", "96", "--height",
                         "72", "--threads", "2", "--samples", "4", "--aov", "N,P,uv,id,mask", "--out", exr],
                        check=True, stdout=subprocess.DEVNULL)
            out = quadra.Renderer(threads=2).render(quadra.load(GLB), width=96, height=72,
                                                    samples=4, aovs=("N", "P", "uv", "id", "mask"))
            planes = [(out.color, "R G B A"), (out.normal, "N.X N.Y N.Z"),
                      (out.position, "P.X P.Y P.Z"), (out.uv, "uv.U uv.V"), (out.mask, "mask"),
                      (out.primitive_id, "id.primitive"), (out.node_id, "id.node"),
                      (out.material_id, "id.material")]
            for array, channels in planes:
                raw = os.path.join(work, "channels.raw")
                run_program([READ_REFERENCE, "--channels", exr, raw] + channels.split(),
                            check=True)
                with open(raw, "rb") as f:
                    stored = f.read()
                self.assertEqual(len(stored), array.nbytes, channels)
                self.assertTrue(stored == array.tobytes(), channels + " differ from the CLI's")
            # Both hold a surface and the background: the comparison is not vacuous.
            self.assertTrue(np.any(out.node_id == 0xFFFFFFFF) and np.any(out.node_id != 0xFFFFFFFF))
            self.assertTrue(np.any((out.mask > 0) & (out.mask < 1)))  # edges at 4 samples


class Animation(unittest.TestCase):
    def test_posed_frames_equal_the_cli_sequence_bit_for_bit(self):
        # BoxAnimated: one unnamed animation, 3.7 s long, no camera (framed
        # once at the rest pose, as the CLI frames a sequence).
        if CLI is None:
            self.skipTest("run by CTest with the CLI, read_reference and model paths")
        scene = quadra.load(ANIMATED)
        self.assertEqual(scene.animations, [""])
        self.assertAlmostEqual(scene.animation_duration(0), 3.7083, places=3)
        renderer = quadra.Renderer(threads=2)
        with tempfile.TemporaryDirectory() as work:
            run_program([CLI, "render", ANIMATED, "--shading", "unlit", "--width", "64",
                         "--height", "48", "--threads", "2", "--sequence", "0:2", "--fps", "2",
                         "--out", os.path.join(work, "f_#.exr")],
                        check=True, stdout=subprocess.DEVNULL)
            colors = []
            for f in range(3):
                scene.set_animation_time(f / 2)
                out = renderer.render(scene, width=64, height=48)
                colors.append(out.color)
                raw = os.path.join(work, "python.raw")
                with open(raw, "wb") as file:
                    file.write(out.color.tobytes() + out.depth.tobytes())
                judged = run_program([READ_REFERENCE, os.path.join(work, f"f_{f}.exr"), raw],
                                     capture_output=True, text=True)
                self.assertEqual(judged.returncode, 0, f"frame {f}: {judged.stdout}{judged.stderr}")
            self.assertFalse(np.array_equal(colors[0], colors[2]))  # the box moved

    def test_bad_animation_or_time_is_an_error(self):
        if CLI is None:
            self.skipTest("run by CTest with the model path")
        scene = quadra.load(ANIMATED)
        with self.assertRaisesRegex(quadra.Error, r"^setAnimationTime: animation 1 is not one of"):
            scene.set_animation_time(0.5, animation=1)
        with self.assertRaisesRegex(quadra.Error, r"^setAnimationTime: seconds inf is not finite$"):
            scene.set_animation_time(float("inf"))
        self.assertEqual(quadra.Scene().animations, [])


def panorama(width=64, height=32):
    """A panorama no symmetry maps onto itself: redder toward +Y, green varying
    around the horizon, bluer below, and a small sun of radiance ~50."""
    u = (np.arange(width, dtype=np.float32) + 0.5) / width
    v = (np.arange(height, dtype=np.float32) + 0.5) / height
    texels = np.empty((height, width, 3), np.float32)
    texels[..., 0] = (0.2 + 0.8 * (1 - v))[:, None]
    texels[..., 1] = (0.5 + 0.5 * np.sin(2 * np.pi * u))[None, :]
    texels[..., 2] = (0.7 * v)[:, None]
    texels[9:11, 20:23] = (50, 45, 40)
    return texels


class LitFromNumpy(unittest.TestCase):
    """shading="pbr" lit by an environment given as an (H, W, 3) float32 array:
    the CLI's frame of an EXR holding the same texels, bit for bit (colour and
    depth through read_reference; the 8-bit target against the CLI's PNG)."""

    def cli_texels(self, work, source):
        """`quadra env SOURCE` written to EXR and read back as (H, W, 3) float32."""
        exr = os.path.join(work, "env.exr")
        line = run_program([CLI, "env", source, "--out", exr], check=True, capture_output=True,
                           text=True).stdout
        fields = dict(word.split("=", 1) for word in line.split() if "=" in word)
        raw = os.path.join(work, "env.raw")
        run_program([READ_REFERENCE, "--channels", exr, raw, "R", "G", "B"], check=True)
        texels = np.fromfile(raw, np.float32)
        return exr, texels.reshape(int(fields["height"]), int(fields["width"]), 3)

    def test_array_environment_frame_equals_the_cli_exr_bit_for_bit(self):
        if CLI is None:
            self.skipTest("run by CTest with the CLI and read_reference paths")
        with tempfile.TemporaryDirectory() as work:
            exr, texels = self.cli_texels(work, "builtin:sky")
            frame = os.path.join(work, "cli.exr")
            run_program([CLI, "render", GLB, "--shading", "pbr", "--env", exr, "--width", "64",
                         "--height", "48", "--threads", "2", "--out", frame],
                        check=True, stdout=subprocess.DEVNULL)
            renderer = quadra.Renderer(threads=2)
            out = renderer.render(quadra.load(GLB), width=64, height=48, shading="pbr",
                                  env=texels)
            raw = os.path.join(work, "python.raw")
            with open(raw, "wb") as f:
                f.write(out.color.tobytes() + out.depth.tobytes())
            judged = run_program([READ_REFERENCE, frame, raw], capture_output=True, text=True)
            self.assertEqual(judged.returncode, 0, judged.stdout + judged.stderr)
            # The same texels by name, by file and held in an Environment light alike.
            for env in ("builtin:sky", exr, quadra.Environment(texels)):
                again = renderer.render(quadra.load(GLB), width=64, height=48, shading="pbr",
                                        env=env)
                np.testing.assert_array_equal(again.color, out.color)
            # Another panorama lights another frame: the comparison is not vacuous.
            other = renderer.render(quadra.load(GLB), width=64, height=48, shading="pbr",
                                    env=panorama())
            self.assertFalse(np.array_equal(other.color, out.color))

    def test_options_and_the_8_bit_target_equal_the_clis(self):
        # The CLI's option names as keywords: a turned, scaled, exposed frame
        # without the background, and its ACES-mapped bytes as the PNG's.
        if CLI is None:
            self.skipTest("run by CTest with the CLI and read_reference paths")
        with tempfile.TemporaryDirectory() as work:
            exr, texels = self.cli_texels(work, "builtin:sky")
            frame, png = os.path.join(work, "cli.exr"), os.path.join(work, "cli.png")
            options = ["--env-rotation", "40", "--env-intensity", "1.5", "--exposure", "0.5",
                       "--tonemap", "aces", "--background", "transparent"]
            run_program([CLI, "render", GLB, "--env", exr, "--width", "64", "--height", "48",
                         "--threads", "2", "--out", frame, "--out", png] + options,
                        check=True, stdout=subprocess.DEVNULL)
            scene = quadra.load(GLB)
            renderer = quadra.Renderer(threads=2)
            keywords = dict(width=64, height=48, shading="pbr", env=quadra.Environment(texels),
                            env_rotation=40, env_intensity=1.5, exposure=0.5, tonemap="aces",
                            background="transparent")
            out = renderer.render(scene, **keywords)
            raw = os.path.join(work, "python.raw")
            with open(raw, "wb") as f:
                f.write(out.color.tobytes() + out.depth.tobytes())
            judged = run_program([READ_REFERENCE, frame, raw], capture_output=True, text=True)
            self.assertEqual(judged.returncode, 0, judged.stdout + judged.stderr)
            srgb = renderer.render(scene, format="rgba8srgb", **keywords)
            self.assertEqual(srgb.color.dtype, np.uint8)
            self.assertEqual(srgb.color.shape, (48, 64, 4))
            np.testing.assert_array_equal(srgb.color, read_png_rgba8(png))

    def test_environment_holds_the_repaired_texels(self):
        texels = panorama()
        texels[0, 0, 0] = np.nan
        texels[1, 2, 1] = -4
        texels[2, 3, 2] = np.inf
        env = quadra.Environment(texels)
        self.assertEqual((env.width, env.height, env.name), (64, 32, "texels"))
        self.assertEqual(env.repaired_values, 3)
        expected = texels.copy()
        expected[0, 0, 0] = 0
        expected[1, 2, 1] = 0
        expected[2, 3, 2] = 2.0 ** 32
        np.testing.assert_array_equal(env.texels, expected)
        a = quadra.Renderer(threads=1).render(quad_scene(), width=16, height=16, shading="pbr",
                                              env=env)
        b = quadra.Renderer(threads=1).render(quad_scene(), width=16, height=16, shading="pbr",
                                              env=expected)
        np.testing.assert_array_equal(a.color, b.color)
        self.assertTrue(np.all(np.isfinite(a.color)))

    def test_bad_environments_fail_cleanly(self):
        renderer = quadra.Renderer(threads=1)
        with self.assertRaisesRegex(ValueError, r"^env: shape \(32, 64\), expected \(H, W, 3\)$"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr",
                            env=np.zeros((32, 64), np.float32))
        with self.assertRaisesRegex(ValueError, r"^env: dtype float64, expected float32$"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr",
                            env=np.zeros((4, 8, 3)))
        with self.assertRaisesRegex(ValueError, r"^texels: shape \(4, 8, 4\), expected"):
            quadra.Environment(np.zeros((4, 8, 4), np.float32))
        with self.assertRaisesRegex(ValueError, r"^env: expected an Environment"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr", env=3)
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*at least 2 texels[^\n]*$"):
            quadra.Environment(np.zeros((0, 0, 3), np.float32))
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*no-such-panorama\.hdr[^\n]*$"):
            quadra.Environment("no-such-panorama.hdr")
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*builtin:nowhere[^\n]*$"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr", env="builtin:nowhere")
        with self.assertRaisesRegex(ValueError, r"^tonemap: 'filmic' is not one of"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr", tonemap="filmic")
        with self.assertRaisesRegex(ValueError, r"^background: 'sky' is not one of"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr", background="sky")
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*exposure[^\n]*$"):
            renderer.render(quad_scene(), width=8, height=8, shading="pbr", exposure=100)


def read_png_rgba8(path):
    """An 8-bit RGBA PNG as quadra writes it (one IHDR, IDAT chunks, every row
    of filter type None: engine/io/image_io.cpp) as an (H, W, 4) uint8 array."""
    import struct
    import zlib
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 6), "not 8-bit RGBA"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    rows = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(height, 1 + width * 4)
    assert not rows[:, 0].any(), "a row with a filter other than None"
    return rows[:, 1:].reshape(height, width, 4)


class Misuse(unittest.TestCase):
    def test_error_is_a_runtime_error(self):
        self.assertTrue(issubclass(quadra.Error, RuntimeError))

    def test_wrong_dtype_or_shape_is_a_value_error_naming_the_argument(self):
        scene = quadra.Scene()
        with self.assertRaisesRegex(ValueError, r"^positions: dtype float64, expected float32$"):
            scene.add_mesh(QUAD_POSITIONS.astype(np.float64), QUAD_INDICES)
        with self.assertRaisesRegex(ValueError, r"^positions: shape \(4, 2\), expected \(N, 3\)$"):
            scene.add_mesh(QUAD_POSITIONS[:, :2], QUAD_INDICES)
        with self.assertRaisesRegex(ValueError, r"^indices: dtype int64, expected uint16 or uint32$"):
            scene.add_mesh(QUAD_POSITIONS, QUAD_INDICES.astype(np.int64))
        with self.assertRaisesRegex(ValueError, r"^texels: shape \(2, 2, 3\), expected \(H, W, 4\)$"):
            scene.add_texture(np.zeros((2, 2, 3), np.uint8))
        with self.assertRaisesRegex(ValueError, r"^texels: dtype int32"):
            scene.add_texture(np.zeros((2, 2, 4), np.int32))
        with self.assertRaisesRegex(ValueError, r"^transform: shape \(3, 3\), expected \(4, 4\)$"):
            scene.add_instance(0, 0, np.eye(3))
        with self.assertRaisesRegex(ValueError, r"^filter: 'cubic' is not one of nearest, "):
            scene.add_texture(np.zeros((1, 1, 4), np.uint8), filter="cubic")
        with self.assertRaisesRegex(ValueError, r"^aovs: 'motion' is not one of N, P, uv, id, mask$"):
            quadra.Renderer(threads=1).render(quad_scene(), width=8, height=8, aovs=["N", "motion"])
        with self.assertRaisesRegex(ValueError, r"^width, height: 0x8 is not within"):
            quadra.Renderer(threads=1).render(quad_scene(), width=0, height=8)
        self.assertEqual(scene.mesh_count, 0)

    def test_the_public_apis_errors_keep_their_one_line_message(self):
        scene = quadra.Scene()
        bad = QUAD_INDICES.copy()
        bad[1, 2] = 7
        with self.assertRaisesRegex(quadra.Error, r"^mesh: index 7 .*out of range for 4 vertices$"):
            scene.add_mesh(QUAD_POSITIONS, bad)
        mesh = scene.add_mesh(QUAD_POSITIONS, QUAD_INDICES)
        material = scene.add_material()
        nan = np.eye(4)
        nan[0, 3] = np.nan
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*(NaN|finite)[^\n]*$"):
            scene.add_instance(mesh, material, nan)
        self.assertEqual(scene.instance_count, 0)
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*texture[^\n]*$"):
            scene.add_texture(np.zeros((0, 4, 4), np.uint8))
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*samples[^\n]*$"):
            quadra.Renderer(threads=1).render(quad_scene(), width=8, height=8, samples=3)
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*over the memory budget of 1000 bytes"):
            quadra.Renderer(threads=1).render(quad_scene(), width=8, height=8, max_memory=1000)
        with self.assertRaisesRegex(quadra.Error, r"no-such-file\.glb"):
            quadra.load("no-such-file.glb")

    def test_load_options_guard_the_load(self):
        if CLI is None:
            self.skipTest("run by CTest with the model path")
        with self.assertRaisesRegex(quadra.Error, r"^[^\n]*over the memory budget of 1000 bytes"):
            quadra.load(GLB, max_memory=1000)
        with self.assertRaisesRegex(quadra.Error, r"scene 5 does not exist"):
            quadra.load(GLB, scene=5)
        with self.assertRaisesRegex(quadra.Error, r"/no/such/folder"):
            quadra.load(GLB, allowed_paths=["/no/such/folder"])
        scene = quadra.load(GLB, allowed_paths=[os.path.dirname(GLB)], scene=0)
        out = quadra.Renderer(threads=1).render(scene, width=16, height=16)
        self.assertGreater(int((out.color[..., 3] > 0).sum()), 16)


if __name__ == "__main__":
    # argv holds the paths above, not unittest's options.
    result = unittest.main(argv=sys.argv[:1], exit=False, verbosity=2).result
    ran = result.testsRun - len(result.skipped)
    if ran == 0:
        print("test_quadra.py: no test ran", file=sys.stderr)
    sys.exit(0 if result.wasSuccessful() and ran > 0 else 1)
