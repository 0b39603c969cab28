"""What each figure of analysis.reproduce measures, pinned: per sweep the
techniques it times with EVERY parameter that changes what is measured set
explicitly, its scenes, sizes and cameras. A later change of a technique's
defaults then cannot change a figure; a parameter added to a technique
fails tests/reproduce_test.py (with the built oitbench) until it is pinned
here or listed in UNPINNED with the reason it cannot change a measurement.

analysis.reproduce builds its sweeps from this table (one way: the sizes,
series and pins live here only); `--list-commands` prints what it plans,
and the test checks every planned bench against this table.

Pins that select the papers' variants (ILLUSTRATION_BUFFER_PAPER,
PEELING_CANONICAL, BUCKETED_KBUFFER_PAPER, the *_PAPER_SLOTS of the k-buffers)
name the paper and section; the other values are the build's defaults of
2026-11-27, frozen (slot_layout=full: the default of 2026-11-28).
"""
from collections import namedtuple

# A timed series: a technique and its pinned parameters, and the label the
# plots and the README give it.
Series = namedtuple("Series", "technique pins label")
# A figure's sweep: the plots drawn from it, its series (a sweep over
# every timed technique lists one series per technique; the driver keeps
# those the build has), what scenes it times, and the sizes per mode.
Figure = namedtuple("Figure", "sweep plots paper series scenes sizes cameras")

# Parameters that cannot change a measurement, with the reason: never set.
UNPINNED = {
    ("bucketed_kbuffer", "color_transfer_file"): "empty = none; a file would override color_transfer, which is pinned",
    ("bucketed_kbuffer", "opacity_transfer_file"): "empty = none; a file would override opacity_transfer, pinned",
}

# carnecky2013 Algorithm 1 (per-pixel linked lists, 4.2), eq. 8-9 iterated
# step by step (5.4) on every fragment every iteration (no skipping, no
# tolerance), the colour stored in the fill record: the papers' path
# (pastyrik2016 builds on the same buffer). `preset=paper`, where the build
# has it, stands for these five.
ILLUSTRATION_BUFFER_PAPER = {"storage": "linked", "diffusion": "steps", "skip_converged": "false",
                             "flat_color_records": "false", "diffusion_tolerance": "0"}
ILLUSTRATION_BUFFER_FIXED = {"modulation": "silhouette_halo", "adaptive_alpha": "false", "lambda_alpha": "1",
                             "lambda_beta": "0.05", "lambda_gamma": "0.1", "field_diffusion": "nonphysical",
                             "profile": "none", "exponential_p": "3",
                             "power_p": "0.3", "weight_z": "1", "weight_n": "1", "weld_vertices": "true",
                             "fill": "auto", "normal_variation_scale": "10", "focus_region": "1", "max_per_pixel": "64",
                             "initial_nodes_per_pixel": "8", "measure_accuracy": "false",
                             "accuracy_footprints": "1.5"}


def illustration_buffer(**figure_knobs):
    """The illustration buffer on the papers' path with the figure's own
    knobs (iterations, neighbors, sort)."""
    return {**ILLUSTRATION_BUFFER_FIXED, **ILLUSTRATION_BUFFER_PAPER, **figure_knobs}


# carnecky2013 section 7: one diffusion iteration (its solve pass), its own
# neighbour search (Algorithm 2), the sort of its section 4.3 (an array).
CARNECKY = illustration_buffer(iterations="1", neighbors="heuristic", sort="array")
# carnecky2013 Figs. 9-13 (images): its path at the 20 iterations of its
# Fig. 9 and 12(b); each image sets its own knobs (modulation, and Fig. 9's
# below) on top.
CARNECKY_IMAGES = illustration_buffer(iterations="20", neighbors="heuristic", sort="array")
# carnecky2013 Fig. 9's five columns (its table: Diff., Mod., n, lambda_beta,
# lambda_gamma, p): eq. 9; eq. 9 with eq. 10 (p = 3); eq. 8; eq. 8 with
# eq. 11 (p = 0.3); eq. 8 with n = 100. lambda_gamma = 0.1 in all five,
# lambda_beta = 0.05 with eq. 9 and 1.0 with eq. 8. Every knob of the
# table set in each column (the rest: CARNECKY_IMAGES).
CARNECKY_FIG9_EQ9 = {"field_diffusion": "nonphysical", "iterations": "20", "lambda_beta": "0.05",
                     "lambda_gamma": "0.1", "profile": "none"}
CARNECKY_FIG9_EQ8 = {**CARNECKY_FIG9_EQ9, "field_diffusion": "homogeneous", "lambda_beta": "1"}
CARNECKY_FIG9 = [
    ("fig09_1_eq9", "eq. 9, n=20, λβ=0.05", CARNECKY_FIG9_EQ9),
    ("fig09_2_eq9_eq10", "eq. 9 + eq. 10 (p=3)", {**CARNECKY_FIG9_EQ9, "profile": "exponential", "exponential_p": "3"}),
    ("fig09_3_eq8", "eq. 8, n=20, λβ=1", CARNECKY_FIG9_EQ8),
    ("fig09_4_eq8_eq11", "eq. 8 + eq. 11 (p=0.3)", {**CARNECKY_FIG9_EQ8, "profile": "power", "power_p": "0.3"}),
    ("fig09_5_eq8_n100", "eq. 8, n=100, λβ=1", {**CARNECKY_FIG9_EQ8, "iterations": "100"}),
]
# pastyrik2016: triangles sharing a vertex index (its Algorithm 3), the
# dynamic sort of the list (its Algorithm 2, the faster in its Fig. 7); the
# paper gives no iteration count: our default of 20, pinned.
PASTYRIK = illustration_buffer(iterations="20", neighbors="triangle_index", sort="dynamic")

# The canonical depth peel (Everitt 2001; Bavoil & Myers 2008 for dual):
# ties in depth peeled in submission order. tie_break=triangle_id (our
# default) peels every tied fragment exactly, at a cost: the peeling figure
# shows both, labelled.
PEELING_CANONICAL = {"max_passes": "64", "early_exit": "true", "tie_break": "submission"}
PEELING_EXACT_TIES = {**PEELING_CANONICAL, "tie_break": "triangle_id"}

KBUFFER = {"k": "16", "tail": "drop", "auto_k_memory_mb": "1024", "slot_layout": "full"}
# murray2016 section 6: the classic dual-pass k-buffer in 64 bits per
# fragment (32-bit depth, RGBA8 colour), the OIT its Figs. 1, 8, 9 time.
KBUFFER_PAPER_SLOTS = {**KBUFFER, "slot_layout": "paper"}
# murray2016: its neighbour query scans the fragment's bucket (section 5,
# Fig. 5, with the reverse check), buckets on whatever the scene. Our slots
# are 20 bytes (a kappa word besides Z, B, colour and normal) unless
# slot_layout=paper, the paper's 128 bits (section 6), which murray_models
# times beside ours; the other sweeps keep ours.
BUCKETED_KBUFFER_FIXED = {"reverse_check": "true", "color_transfer": "mean_curvature_shading",
                          "opacity_transfer": "front_focus", "depth_bits": "16", "curvature_scale": "1",
                          "measure_accuracy": "false", "auto_k_memory_mb": "1024", "slot_layout": "full"}
BUCKETED_KBUFFER_PAPER = {**BUCKETED_KBUFFER_FIXED, "k": "16", "buckets": "on", "neighbor_search": "bucket"}
BUCKETED_KBUFFER_PAPER_SLOTS = {**BUCKETED_KBUFFER_PAPER, "slot_layout": "paper"}

# Every other technique of the comparison at the build's defaults, frozen.
OTHERS = {
    "linked_list": {"sort": "network", "max_per_pixel": "64", "initial_nodes_per_pixel": "8",
                    "pool_sizing": "previous_frame", "storage": "full", "length_classes": "true"},
    "linearized_fragment_buffer": {"sort": "network", "block_size": "16", "backwards_allocation": "true",
                                   "fill": "auto", "scan": "auto", "key_format": "auto", "flat_color_nodes": "true"},
    "adaptive_transparency": {"k": "4"},
    "hybrid_transparency": {"k": "4"},
    "multi_layer_alpha_blending": {"k": "4"},
    "moment_oit": {"moments": "power6", "precision": "float", "moment_bias_scale": "1", "overestimation": "0.25",
                   "wrapping_zone_degrees": "18"},
    "stochastic_transparency": {"samples": "4", "passes": "1", "seed": "1"},
    "weighted_blended": {"weight": "eq10", "precision": "float"},
    "unsorted": {},
}


def comparison_series(k_auto=False, both_ties=True):
    """Every timed technique once, in the paper's order (the peelings
    canonical first, then, with `both_ties`, with exact ties); `k_auto`: the
    k-buffers at k=auto (k = the view's depth complexity)."""
    kbuffer = {**KBUFFER, "k": "auto"} if k_auto else KBUFFER
    bucketed = {**BUCKETED_KBUFFER_PAPER, "k": "auto"} if k_auto else BUCKETED_KBUFFER_PAPER
    peelings = [Series(t, pins, f"{t} tie_break={pins['tie_break']}")
                for t in ("depth_peeling", "dual_depth_peeling")
                for pins in ([PEELING_CANONICAL, PEELING_EXACT_TIES] if both_ties else [PEELING_CANONICAL])]
    return (peelings +
            [Series("linked_list", OTHERS["linked_list"], "linked_list"),
             Series("illustration_buffer", PASTYRIK, "illustration_buffer (pastyrik2016 path)"),
             Series("kbuffer", kbuffer, "kbuffer"),
             Series("bucketed_kbuffer", bucketed, "bucketed_kbuffer (murray2016 bucket query)")]
            + [Series(t, pins, t) for t, pins in OTHERS.items() if t != "linked_list"])


MURRAY_FIG10_K = {"k": "32"}
FIGURES = {
    "murray_fig10": Figure(
        "murray_fig10", ["murray_fig10"], "murray2016 Fig. 10: 512x512, 32 layers, k = 32, 1..32 objects",
        [Series("kbuffer", {**KBUFFER, **MURRAY_FIG10_K}, "kbuffer alone"),
         Series("bucketed_kbuffer", {**BUCKETED_KBUFFER_PAPER, **MURRAY_FIG10_K}, "bucketed (paper: bucket query)"),
         Series("bucketed_kbuffer", {**BUCKETED_KBUFFER_PAPER, **MURRAY_FIG10_K, "buckets": "off"},
                "brute force (buckets=off)"),
         Series("bucketed_kbuffer", {**BUCKETED_KBUFFER_PAPER, **MURRAY_FIG10_K, "neighbor_search": "merge"},
                "merge search (not in the paper)")],
        "quads layers=32 objects=1,2,4,8,16,32", {"quick": [(64, 64)], "full": [(512, 512)]}, "default"),
    "carnecky_fig14": Figure(
        "carnecky_fig14", ["carnecky_fig14"],
        "carnecky2013 Fig. 14: toroid, 128^2..2048^2, one diffusion iteration, random cameras",
        [Series("illustration_buffer", CARNECKY, "illustration_buffer (carnecky2013 path)")],
        "torus", {"quick": [(s, s) for s in (128, 192, 256, 384, 512)],
                  "full": [(s, s) for s in (128, 256, 512, 1024, 2048)]}, "random:3:1 quick, random:32:1 full"),
    "carnecky_fig15": Figure(
        "carnecky_fig15", ["carnecky_fig15"],
        "carnecky2013 Fig. 15: toroid up to 500k triangles at 1024^2, one diffusion iteration",
        [Series("illustration_buffer", CARNECKY, "illustration_buffer (carnecky2013 path)")],
        "torus slices x stacks: 64..65k triangles quick, 256..1M full", {"quick": [(256, 256)], "full": [(1024, 1024)]},
        "random:3:1 quick, random:16:1 full"),
    "models": Figure(
        "models", ["pastyrik_fig8", "pastyrik_fig9", "pastyrik_fig10", "oit_comparison", "pastyrik_fig11_14",
                   "pastyrik_memory", "peeling_stages"],
        "pastyrik2016 Figs. 8-14 and 4.3: 600x600, two positions per model (general, longest list)",
        comparison_series(), "the model catalogue (a quick subset) and the CAD files installed",
        {"quick": [(256, 256)], "full": [(600, 600)]}, "default, max_list:16:1"),
    "pastyrik_fig7": Figure(
        "pastyrik_fig7", ["pastyrik_fig7"],
        "pastyrik2016 Fig. 7: the dynamic sort of the list against the static arrays (3 x 64 entries), 600x600",
        [Series("illustration_buffer", {**PASTYRIK, "sort": "static_arrays"},
                "illustration_buffer sort=static_arrays (pastyrik2016 3.2: selection sort in 3 static arrays of 64)"),
         Series("illustration_buffer", {**PASTYRIK, "sort": "dynamic"},
                "illustration_buffer sort=dynamic (pastyrik2016 Algorithm 2: insertion sort of the list in place)")],
        "as models", {"quick": [(256, 256)], "full": [(600, 600)]}, "default, max_list:16:1"),
    "murray_models": Figure(
        "murray_models", ["murray_fps_ratio"],
        "murray2016 Figs. 1, 8, 9: OIT k-buffer against the stylised bucketed k-buffer, 16 layers, 1000x1000 "
        "(Fig. 8's bike: 1200x800)",
        [Series("kbuffer", KBUFFER_PAPER_SLOTS, "kbuffer (OIT; the paper's 8 B slots)"),
         Series("bucketed_kbuffer", BUCKETED_KBUFFER_PAPER_SLOTS,
                "bucketed_kbuffer (paper's bucket query; the paper's 16 B slots)"),
         Series("kbuffer", KBUFFER, "kbuffer (OIT; our 24 B slots)"),
         Series("bucketed_kbuffer", BUCKETED_KBUFFER_PAPER, "bucketed_kbuffer (paper's bucket query; our 20 B slots)")],
        "as models", {"quick": [(256, 256)], "full": [(1000, 1000), (1200, 800)]}, "default"),
    "psi_scenes": Figure(
        "psi_scenes", ["pastyrik_psi"], "pastyrik2016 section 5: synthetic scenes of Psi 0..1, 600x600",
        [Series("illustration_buffer", PASTYRIK, "illustration_buffer (pastyrik2016 path)"),
         Series("linked_list", OTHERS["linked_list"], "linked_list")],
        "PSI_SCENES of analysis.reproduce", {"quick": [(256, 256)], "full": [(600, 600)]}, "default"),
    "layers": Figure(
        "layers", ["time_per_fragment"], "no paper figure: 4..64 layers at 512^2",
        comparison_series(k_auto=True, both_ties=False), "quads layers=4..64", {"quick": [(128, 128)], "full": [(512, 512)]},
        "default"),
}

