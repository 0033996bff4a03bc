# The steady image the add-on renders (F12 through the SLOWLIGHT engine: the scene written by the
# add-on, slowlight run as a child process, steady.exr loaded into the render result) against
# Cycles rendering the same Blender scene: a point lamp, an emissive quad, a rough metal sphere
# (followed by slowlight's camera paths), a blue plastic sphere (gathered) and a hazy box
# (Cycles' volume in the same box). Both are linear radiance (W sr^-1 m^-2); their means over
# the image must agree within 3 %. The regions' ratios (each sphere's, from the camera's
# projection) are printed; SLOWLIGHT_TEST_CYCLES_SEEDS="1 2" also renders Cycles' second seed
# and prints seed 2 / seed 1 per region (Cycles' own noise; docs/blender.md has the figures);
# SLOWLIGHT_TEST_PASSES and SLOWLIGHT_TEST_CYCLES_SAMPLES set the two renderers' effort.
#
# Cycles draws the Principled surfaces themselves: slowlight draws a non-metal Principled BSDF
# as Cycles 3.4 does (Burley's diffuse under the GGX layer added on top, docs/materials.md, "The
# diffuse base"), and a metal as the same GGX conductor.
import os
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402
import exr_image  # noqa: E402
import showcase_scene  # noqa: E402

PASSES = int(os.environ.get("SLOWLIGHT_TEST_PASSES", "48"))  # slowlight's, of 100 000 photons
CYCLES_SAMPLES = int(os.environ.get("SLOWLIGHT_TEST_CYCLES_SAMPLES", "128"))
CYCLES_SEEDS = [int(s) for s in os.environ.get("SLOWLIGHT_TEST_CYCLES_SEEDS", "1").split()]
W, H = 96, 72

zip_path, program, work = addon_env.args()
scene = showcase_scene.build(W, H)
addon_env.install(zip_path)
check = addon_env.check


def write_exr(path):
    s = scene.render.image_settings
    s.file_format, s.color_depth, s.color_mode = "OPEN_EXR", "32", "RGB"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


scene.render.engine = 'SLOWLIGHT'
st = scene.slowlight
st.program, st.passes, st.photons = program, PASSES, 100000
slow = os.path.join(work, "slowlight.exr")
write_exr(slow)
check(os.path.exists(slow), "F12 with the slowlight engine wrote the steady image")


def inside_sphere(centre_radius):
    """A square of pixels inside a sphere's image: centred on its centre's projection, half a side
    0.6 x the projected radius (a square inside the disc; the disc is a little larger still)."""
    centre, radius = centre_radius
    cam = scene.camera
    right = cam.matrix_world.to_3x3().col[0].normalized()
    c, e = world_to_camera_view(scene, cam, centre), world_to_camera_view(scene, cam, centre + radius * right)
    x, y, r = c.x * W, (1 - c.y) * H, (e.x - c.x) * W
    half = max(1, int(0.6 * r))
    return (int(x) - half, int(x) + half, int(y) - half, int(y) + half)


regions = {"whole image": None, "floor, lower third": (0, W, 48, H), "wall, top rows": (0, W, 0, 12),
           "metal sphere": inside_sphere(showcase_scene.METAL_SPHERE),
           "plastic sphere": inside_sphere(showcase_scene.PLASTIC_SPHERE)}
print("regions [x0, x1, y0, y1), rows from the top:", regions)

scene.render.engine = "CYCLES"
cy = scene.cycles
cy.device, cy.samples = "CPU", CYCLES_SAMPLES
cy.use_adaptive_sampling = cy.use_denoising = False
cy.max_bounces = cy.diffuse_bounces = cy.glossy_bounces = cy.volume_bounces = 64
cy.transmission_bounces = cy.transparent_max_bounces = 64
cy.caustics_reflective = cy.caustics_refractive = True
cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
cy.blur_glossy = 0.0  # no "Filter Glossy": it makes glossy surfaces met after a diffuse bounce rougher
cy.pixel_filter_type, cy.filter_width = "BOX", 1.0
scene.view_settings.view_transform = "Standard"
refs = []
for seed in CYCLES_SEEDS:
    cy.seed = seed
    refs.append(os.path.join(work, "cycles_seed%d.exr" % seed))
    write_exr(refs[-1])

a, b = exr_image.load(slow), exr_image.load(refs[0])
check((len(a), len(a[0])) == (H, W) and (len(b), len(b[0])) == (H, W), "both images are %d x %d" % (W, H))
others = [exr_image.load(r) for r in refs[1:]]
for name, rect in regions.items():
    ma, mb = exr_image.mean(a, rect), exr_image.mean(b, rect)
    noise = "".join("  cycles seed %d / seed %d %.4f" % (seed, CYCLES_SEEDS[0], exr_image.mean(o, rect) / mb)
                    for seed, o in zip(CYCLES_SEEDS[1:], others))
    print("%-20s slowlight %.6f  cycles %.6f  ratio %.4f%s" % (name, ma, mb, ma / mb, noise))
ratio = exr_image.mean(a) / exr_image.mean(b)
check(abs(ratio - 1) < 0.03, "the image means agree within 3 %% (slowlight / Cycles = %.4f)" % ratio)
# Each sphere on its own, loosely: at the test's 48 passes the gather still reads a small curved object's
# indirect light 6-8 % low (a Lambertian sphere as much; it goes with more passes) and Cycles'
# 128 samples leave the metal's highlight a few % noisy (docs/blender.md). 15 % still catches a
# sphere drawn as the wrong kind of surface: as a mirror the metal's highlight shrinks to a point.
for name in ("metal sphere", "plastic sphere"):
    r = exr_image.mean(a, regions[name]) / exr_image.mean(b, regions[name])
    check(abs(r - 1) < 0.15, "the %s agrees within 15 %% (slowlight / Cycles = %.4f)" % (name, r))
