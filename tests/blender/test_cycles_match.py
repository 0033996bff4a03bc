# The steady image the add-on renders (F12 through the SLOWLIGHT engine: the scene written by the
# add-on, slowlight run as a child process, steady.exr loaded into the render result) against
# Cycles rendering the same Blender scene: a point lamp, an emissive quad, a polished metal sphere
# and a hazy box (Cycles' volume in the same box). Both are linear radiance (W sr^-1 m^-2);
# their means over the image must agree within 3 %.
#
# Cycles draws the Principled surfaces themselves: slowlight draws a non-metal Principled BSDF
# as Cycles 3.4 does (Burley's diffuse under the GGX layer added on top, docs/materials.md, "The
# diffuse base"); the metal sphere (roughness 0.05) is a Principled BSDF in both.
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(__file__))
import addon_env  # noqa: E402
import exr_image  # noqa: E402
import showcase_scene  # noqa: E402

CYCLES_SAMPLES = int(os.environ.get("SLOWLIGHT_TEST_CYCLES_SAMPLES", "128"))

zip_path, program, work = addon_env.args()
scene = showcase_scene.build(96, 72)
addon_env.install(zip_path)
check = addon_env.check


def write_exr(path):
    s = scene.render.image_settings
    s.file_format, s.color_depth, s.color_mode = "OPEN_EXR", "32", "RGB"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


scene.render.engine = 'SLOWLIGHT'
st = scene.slowlight
st.program, st.passes, st.photons = program, 48, 100000
slow = os.path.join(work, "slowlight.exr")
write_exr(slow)
check(os.path.exists(slow), "F12 with the slowlight engine wrote the steady image")

scene.render.engine = "CYCLES"
cy = scene.cycles
cy.device, cy.samples, cy.seed = "CPU", CYCLES_SAMPLES, 1
cy.use_adaptive_sampling = cy.use_denoising = False
cy.max_bounces = cy.diffuse_bounces = cy.glossy_bounces = cy.volume_bounces = 64
cy.transmission_bounces = cy.transparent_max_bounces = 64
cy.caustics_reflective = cy.caustics_refractive = True
cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
cy.pixel_filter_type, cy.filter_width = "BOX", 1.0
scene.view_settings.view_transform = "Standard"
ref = os.path.join(work, "cycles.exr")
write_exr(ref)

a, b = exr_image.load(slow), exr_image.load(ref)
check((len(a), len(a[0])) == (72, 96) and (len(b), len(b[0])) == (72, 96), "both images are 96 x 72")
regions = {"whole image": None, "floor, lower third": (0, 96, 48, 72), "wall, top rows": (0, 96, 0, 12)}
for name, rect in regions.items():
    ma, mb = exr_image.mean(a, rect), exr_image.mean(b, rect)
    print("%-20s slowlight %.6f  cycles %.6f  ratio %.4f" % (name, ma, mb, ma / mb))
ratio = exr_image.mean(a) / exr_image.mean(b)
check(abs(ratio - 1) < 0.03, "the image means agree within 3 %% (slowlight / Cycles = %.4f)" % ratio)
