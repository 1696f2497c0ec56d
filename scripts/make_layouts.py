#!/usr/bin/env python3
"""Generates assets/layouts/<id>.json for the five research skins.

The JSON files are what the program reads; this script documents how their
geometry was derived from the papers (../shared/seeds/) and makes it
reproducible. Run from the repository root:  python3 scripts/make_layouts.py
Python 3 standard library only. Output is deterministic (same bytes each run).

Map convention for every skin: an unwrapped 2-D map in millimetres, x to the
right, y downwards. Where a paper leaves a dimension or a count open, the
choice made here is stated next to it and in the layout's description.
"""

import json
import math
import os
import sys

LAYOUT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "layouts")


def rounded(value):
    """Rounds map numbers to 1 micrometre so the JSON stays readable and stable."""
    result = round(value, 3)
    return 0.0 if result == 0 else result


def taxel(taxel_id, name, body_part, x, y, w, h, area, shape, channels):
    return {
        "id": taxel_id,
        "name": name,
        "body_part": body_part,
        "x": rounded(x),
        "y": rounded(y),
        "w": rounded(w),
        "h": rounded(h),
        "area": rounded(area),
        "shape": shape,
        "channels": channels,
    }


def group(group_id, kind, name, taxels):
    return {"id": group_id, "kind": kind, "name": name, "taxels": taxels}


def layout(layout_id, name, description, rate, modalities, display, channels, taxels, groups,
           disjoint_kinds, classes, outline=None):
    result = {
        "id": layout_id,
        "name": name,
        "description": description,
        "map_unit": "mm",
        "sample_rate_hz": rate,
        "modalities": modalities,
        "display": display,
        "channels": channels,
        "taxels": taxels,
        "groups": groups,
        "disjoint_kinds": disjoint_kinds,
        "classes": classes,
    }
    if outline:
        result["outline"] = [[[rounded(x), rounded(y)] for x, y in polygon] for polygon in outline]
    return result


def assert_no_overlap(taxels, sheet_of):
    """Fails when two axis-aligned taxel boxes on the same sheet overlap (hexagons are
    checked by centre distance against the flat-to-flat width instead)."""
    by_sheet = {}
    for entry in taxels:
        by_sheet.setdefault(sheet_of(entry), []).append(entry)
    for sheet, members in by_sheet.items():
        for index, first in enumerate(members):
            for second in members[index + 1:]:
                if first["shape"] == "hex":
                    distance = math.hypot(first["x"] - second["x"], first["y"] - second["y"])
                    if distance < min(first["w"], second["w"]) - 1e-2:
                        sys.exit(f"hexagons {first['id']} and {second['id']} overlap on {sheet}")
                    continue
                overlap_x = (first["w"] + second["w"]) / 2 - abs(first["x"] - second["x"])
                overlap_y = (first["h"] + second["h"]) / 2 - abs(first["y"] - second["y"])
                if overlap_x > 1e-2 and overlap_y > 1e-2:
                    sys.exit(f"taxels {first['id']} and {second['id']} overlap on {sheet}")


# ---- nao ------------------------------------------------------------------------------------------
# Paper 000 (Kaboli et al.): 32 Cellular Skin cells, 16 on the front and 16 on the back of NAO's
# upper body; per cell a 3-axis accelerometer, 3 normal-force sensors, 1 proximity and 1
# temperature sensor; packets every 4 ms (250 Hz). The paper gives sensor sizes (Table 2) but not
# the cell size. The cells are hexagonal; we take a side length of 14 mm (flat-to-flat 24.2 mm),
# large enough to carry three 6x6 mm force sensors around a 4x4 mm proximity sensor.
NAO_SIDE_MM = 14.0


def make_nao():
    side = NAO_SIDE_MM
    # Flat-to-flat, pointy-top cells in offset rows; rounded down to the micrometre so the
    # rounded centres of neighbours are never closer than the rounded width.
    width = math.floor(math.sqrt(3.0) * side * 1000.0) / 1000.0
    height = 2.0 * side  # corner-to-corner
    area = 1.5 * math.sqrt(3.0) * side * side  # regular hexagon: (3 sqrt 3 / 2) s^2
    row_pitch = 1.5 * side
    patch_width = 4.5 * width
    patch_gap = 40.0
    modalities = ["ax", "ay", "az", "f1", "f2", "f3", "prox", "temp"]
    units = {"ax": "g", "ay": "g", "az": "g", "f1": "N", "f2": "N", "f3": "N", "prox": "mm",
             "temp": "degC"}
    channels, taxels = [], []
    for cell in range(1, 33):
        back = cell > 16
        index = (cell - 1) % 16
        row, column = divmod(index, 4)
        origin_x = patch_width + patch_gap if back else 0.0
        x = origin_x + width / 2 + column * width + (width / 2 if row % 2 else 0.0)
        y = height / 2 + row * row_pitch
        names = {}
        for modality in modalities:
            channel_name = f"c{cell:02d}.{modality}"
            channels.append({"name": channel_name, "unit": units[modality], "modality": modality})
            names[modality] = channel_name
        part = "torso-back" if back else "torso-front"
        taxels.append(taxel(cell, f"c{cell:02d}", part, x, y, width, height, area, "hex", names))
    assert_no_overlap(taxels, lambda entry: entry["body_part"])
    groups = [
        group("front", "side", "front of the upper body", list(range(1, 17))),
        group("back", "side", "back of the upper body", list(range(17, 33))),
    ]
    description = (
        "NAO humanoid with Cellular Skin (Kaboli et al., paper 000): 32 hexagonal cells, 16 on the "
        "front and 16 on the back of the upper body, each a 4x4 honeycomb; front patch left, back "
        "patch right on the map. Per cell: 3-axis accelerometer (g, +-2 g), 3 normal-force sensors "
        "(N, 0-3 N), proximity (mm, 1-200 mm), temperature (degC). The paper's body parts are the "
        "front and the back (groups of kind 'side'); it names no finer parts. The paper gives no "
        "cell size: we assume a hexagon side of 14 mm (flat-to-flat 24.2 mm, area 509 mm^2). "
        "Cell rows are numbered top to bottom, cells left to right, in cell-id order."
    )
    return layout(
        "nao", "NAO Cellular Skin (32 cells)", description, 250.0, modalities,
        {"modality": "prox", "min": 200.0, "max": 0.0}, channels, taxels, groups, ["side"],
        ["pat", "poke", "punch", "push", "rub", "scratch", "slap", "stroke", "tickle"])


# ---- tsa ------------------------------------------------------------------------------------------
# Paper 001: each basic sheet has 16 round contacts (5 mm diameter, 7 mm between centres, 25 cm^2
# sheet); one front-end module (FEE) reads two sheets; 21 modules on the top of the head, the
# cheeks, back of the head, forehead, arms and thighs (Fig. 7, whose per-location counts the text
# does not give). Our distribution: 3 top of head, 1 + 1 cheeks, 2 forehead, 4 back of head,
# 3 + 3 arms, 2 + 2 thighs = 21.
TSA_LOCATIONS = [
    # id, name, module centres on the map (front view: the robot's right on the map's left; the
    # back of the head drawn above the top of the head, as if unfolded over it). The simulator
    # reads these positions (a palm near a sheet's edge reaches the next sheet of the same
    # location), so only whole locations are moved on the map, never a module within one: the
    # modules of a location keep their distances (125 mm across the head, 70 mm down a limb).
    ("head-top", "top of head", [(-125.0, 46.0), (0.0, 46.0), (125.0, 46.0)]),
    ("cheek-left", "left cheek", [(62.5, 138.0)]),
    ("cheek-right", "right cheek", [(-62.5, 138.0)]),
    ("forehead", "forehead", [(-62.5, 92.0), (62.5, 92.0)]),
    ("head-back", "back of head", [(-187.5, 0.0), (-62.5, 0.0), (62.5, 0.0), (187.5, 0.0)]),
    ("arm-left", "left arm", [(157.5, 220.0), (157.5, 290.0), (157.5, 360.0)]),
    ("arm-right", "right arm", [(-157.5, 220.0), (-157.5, 290.0), (-157.5, 360.0)]),
    ("thigh-left", "left thigh", [(48.5, 330.0), (48.5, 400.0)]),
    ("thigh-right", "right thigh", [(-48.5, 330.0), (-48.5, 400.0)]),
]


def chamfered_box(left, top, right, bottom, corner):
    """A rectangle with its corners cut at 45 degrees, clockwise from the top left."""
    return [[left + corner, top], [right - corner, top], [right, top + corner],
            [right, bottom - corner], [right - corner, bottom], [left + corner, bottom],
            [left, bottom - corner], [left, top + corner]]


# The robot's silhouette around the modules (a drawing only: head, neck and torso, arms, thighs),
# a few millimetres clear of every pad. The torso carries no sensor.
TSA_OUTLINE = [
    # head: wide at the back of the head, a jaw below the cheeks
    [[-205.0, -35.0], [205.0, -35.0], [242.0, -8.0], [242.0, 100.0], [125.0, 170.0],
     [-125.0, 170.0], [-242.0, 100.0], [-242.0, -8.0]],
    # neck, shoulders and torso down to the hips
    [[-40.0, 170.0], [40.0, 170.0], [40.0, 184.0], [110.0, 196.0], [110.0, 308.0],
     [-110.0, 308.0], [-110.0, 196.0], [-40.0, 184.0]],
    chamfered_box(-207.0, 190.0, -113.0, 384.0, 10.0),  # right arm
    chamfered_box(113.0, 190.0, 207.0, 384.0, 10.0),  # left arm
    chamfered_box(-99.0, 308.0, -3.0, 424.0, 8.0),  # right thigh
    chamfered_box(3.0, 308.0, 99.0, 424.0, 8.0),  # left thigh
]
TSA_PAD_DIAMETER_MM = 5.0
TSA_PAD_PITCH_MM = 7.0
TSA_SHEET_MM = 50.0  # 25 cm^2 per sheet
TSA_SHEET_GAP_MM = 5.0


def make_tsa():
    pad_area = math.pi * (TSA_PAD_DIAMETER_MM / 2) ** 2
    sheet_offset = (TSA_SHEET_MM + TSA_SHEET_GAP_MM) / 2
    channels, taxels, groups = [], [], []
    location_groups, sheet_groups, module_groups = [], [], []
    module = 0
    for location_id, location_name, centres in TSA_LOCATIONS:
        location_taxels = []
        for centre_x, centre_y in centres:
            module += 1
            module_taxels = []
            for sheet in (1, 2):
                sheet_x = centre_x + (sheet_offset if sheet == 2 else -sheet_offset)
                sheet_taxels = []
                for pad in range(16):
                    row, column = divmod(pad, 4)
                    name = f"m{module:02d}.s{sheet}.p{pad:02d}"
                    taxel_id = len(taxels)
                    channels.append({"name": name, "unit": "counts", "modality": "cap"})
                    x = sheet_x + (column - 1.5) * TSA_PAD_PITCH_MM
                    y = centre_y + (row - 1.5) * TSA_PAD_PITCH_MM
                    taxels.append(taxel(taxel_id, name, location_id, x, y, TSA_PAD_DIAMETER_MM,
                                        TSA_PAD_DIAMETER_MM, pad_area, "circle", {"cap": name}))
                    sheet_taxels.append(taxel_id)
                sheet_groups.append(group(f"m{module:02d}.s{sheet}", "sheet",
                                          f"module {module} sheet {sheet}", sheet_taxels))
                module_taxels += sheet_taxels
            module_groups.append(group(f"module-{module:02d}", "module",
                                       f"module {module} ({location_name})", module_taxels))
            location_taxels += module_taxels
        location_groups.append(group(location_id, "location", location_name, location_taxels))
    assert module == 21 and len(taxels) == 672
    groups = location_groups + module_groups + sheet_groups
    assert_no_overlap(taxels, lambda entry: entry["name"][:6])
    description = (
        "Event-triggered capacitive tactile sensor arrays inside the ABS shell of a social robot "
        "(paper 001): 21 front-end modules x 2 sheets x 4x4 round contacts (5 mm diameter, 7 mm "
        "pitch, 25 cm^2 sheet), 12-bit, 8 Hz frames, no intensity. Channel mMM.sS.pPP = module MM, "
        "sheet S, pad PP (row-major, row 0 on top); sheet location code (spec 2.9) = "
        "2*(MM-1)+S. The paper's Fig. 7 fixes the module locations but not the count per location; "
        "we assume 3 top of head, 1 left cheek, 1 right cheek, 2 forehead, 4 back of head, 3 per "
        "arm, 2 per thigh. Map: front view (the robot's right on the map's left), the back of the "
        "head drawn above the top of the head, arms at the sides, thighs below; the two sheets of "
        "a module side by side. Classes: T1 random momentary tapping, T2 random slow sliding, "
        "T3 finger sliding, T4 random finger poking, T5 palm momentary tapping, T6 palm "
        "momentary sliding."
    )
    return layout(
        "tsa", "Capacitive TSA on an ABS shell (21 modules)", description, 8.0, ["cap"],
        {"modality": "cap", "min": 0.0, "max": 4095.0}, channels, taxels, groups,
        ["location", "module", "sheet"], ["T1", "T2", "T3", "T4", "T5", "T6"], TSA_OUTLINE)


# ---- fur ------------------------------------------------------------------------------------------
# Paper 002 (Mueller, Schroeter, Gross): 10 row lines switched by I/O pins x 8 ADC column lines, the
# cell count doubled by a diode per column (the second half of the columns is read with reversed
# current): 10 x 16 = 160 cells. Cells are 2x2 cm on top of the head growing to 4x4 cm below, with a
# 3 mm gap between electrodes. Fig. 4 (the unwrapped matrix) is not in the text; we grow the cell
# size linearly from row 0 (top, 20 mm) to row 9 (bottom, 40 mm) and centre every row on the head's
# midline, which gives the fan shape of an unwrapped dome.
FUR_ROWS = 10
FUR_COLUMNS = 16
FUR_GAP_MM = 3.0


def fur_cell_size(row):
    return 20.0 + 20.0 * row / (FUR_ROWS - 1)


def make_fur():
    channels, taxels = [], []
    row_top = 0.0
    row_groups = []
    for row in range(FUR_ROWS):
        size = fur_cell_size(row)
        row_width = FUR_COLUMNS * size + (FUR_COLUMNS - 1) * FUR_GAP_MM
        y = row_top + size / 2
        members = []
        for column in range(FUR_COLUMNS):
            index = row * FUR_COLUMNS + column
            name = f"f{index:03d}"
            channels.append({"name": name, "unit": "counts", "modality": "pressure"})
            x = -row_width / 2 + size / 2 + column * (size + FUR_GAP_MM)
            region = "top" if row < 3 else ("middle" if row < 7 else "lower")
            taxels.append(taxel(index, f"r{row}c{column:02d}", f"head-{region}", x, y, size, size,
                                size * size, "rect", {"pressure": name}))
            members.append(index)
        row_groups.append(group(f"row-{row:02d}", "row", f"matrix row {row}", members))
        row_top += size + FUR_GAP_MM
    assert_no_overlap(taxels, lambda entry: "head")
    regions = [
        group("top", "region", "top of head",
              [entry["id"] for entry in taxels if entry["body_part"] == "head-top"]),
        group("middle", "region", "middle of head",
              [entry["id"] for entry in taxels if entry["body_part"] == "head-middle"]),
        group("lower", "region", "lower head",
              [entry["id"] for entry in taxels if entry["body_part"] == "head-lower"]),
    ]
    description = (
        "Smart fur pressure matrix on the head of a SCITOS-G3 companion robot (paper 002): 10 row "
        "lines x 8 ADC columns doubled by a diode per column = 160 piezo-resistive cells, 10-bit, "
        "15 Hz. Channel fNNN = cell NNN = row*16 + column; columns 0-7 are read with forward "
        "current on ADC line = column, columns 8-15 with reversed current on ADC line = column-8. "
        "Raw values fall when pressed (spec 3.1: use 1023 - raw). Cells grow from 20x20 mm (row 0, "
        "top) to 40x40 mm (row 9, bottom) linearly (the paper gives only the end sizes), 3 mm gap, "
        "every row centred on the head's midline; area = cell size squared (mm^2). The display "
        "scale is reversed (1023 dark, 0 bright) because raw values fall under pressure. Regions: "
        "top rows 0-2, middle 3-6, lower 7-9 (the paper: highest density on top of the head)."
    )
    return layout(
        "fur", "Smart fur on a robot head (160 cells)", description, 15.0, ["pressure"],
        {"modality": "pressure", "min": 1023.0, "max": 0.0}, channels, taxels,
        regions + row_groups, ["region", "row"],
        ["slap", "pat", "fondle", "stroke", "tickle", "push"])


# ---- robovie --------------------------------------------------------------------------------------
# Paper 003: 274 PVDF piezo films (3x3 cm or 5x5 cm) embedded in soft silicone over the whole body of
# Robovie-IIF, 16-bit A/D at 100 Hz; sensors named by body part (e.g. "F-body (upper)"), adjacent
# sensors have close numbers. Fig. 4 (film positions) is not in the text and no per-part counts are
# given: the distribution below is ours. Each part lists its blocks: (side, rows, columns, film size,
# block centre x, block top y). Front view: robot's right on the map's left (x < 0); back view:
# robot's left on the map's left. The back view is shifted right by ROBOVIE_BACK_OFFSET_MM.
ROBOVIE_BACK_OFFSET_MM = 640.0
ROBOVIE_FILM_GAP_MM = 5.0


def mirrored(parts_right):
    """Turns the right-hand parts into (right, left) pairs; the left side is the mirror image on the
    front view and the same place on the back view (seen from behind)."""
    result = []
    for part_id, part_name, blocks in parts_right:
        right = []
        left = []
        for side, rows, columns, film, centre_x, top in blocks:
            front_x = -abs(centre_x)
            if side == "front":
                right.append((side, rows, columns, film, front_x, top))
                left.append((side, rows, columns, film, -front_x, top))
            else:
                right.append((side, rows, columns, film, -front_x, top))
                left.append((side, rows, columns, film, front_x, top))
        result.append((part_id + "-right", "right " + part_name, right))
        result.append((part_id + "-left", "left " + part_name, left))
    return result


ROBOVIE_PARTS = [
    ("head", "head (back)", [("back", 4, 4, 30.0, 0.0, 0.0)]),
    ("face", "face", [("front", 3, 4, 30.0, 0.0, 0.0)]),
    ("neck", "neck", [("front", 1, 3, 30.0, 0.0, 110.0), ("back", 1, 3, 30.0, 0.0, 145.0)]),
] + mirrored([
    ("shoulder", "shoulder", [("front", 1, 3, 30.0, 140.0, 150.0),
                              ("back", 1, 3, 30.0, 140.0, 150.0)]),
]) + [
    ("chest-upper", "upper chest", [("front", 3, 4, 50.0, 0.0, 190.0)]),
    ("chest-lower", "lower chest", [("front", 3, 4, 50.0, 0.0, 360.0)]),
    ("back-upper", "upper back", [("back", 3, 4, 50.0, 0.0, 190.0)]),
    ("back-lower", "lower back", [("back", 3, 4, 50.0, 0.0, 360.0)]),
] + mirrored([
    ("side", "flank", [("front", 3, 1, 50.0, 137.5, 360.0),
                              ("back", 3, 1, 50.0, 137.5, 360.0)]),
    ("upper-arm", "upper arm", [("front", 5, 2, 30.0, 210.0, 190.0),
                                ("back", 5, 2, 30.0, 210.0, 190.0)]),
    ("forearm", "forearm", [("front", 5, 2, 30.0, 210.0, 370.0),
                            ("back", 5, 2, 30.0, 210.0, 370.0)]),
    ("hand", "hand", [("front", 2, 2, 30.0, 210.0, 550.0), ("back", 2, 2, 30.0, 210.0, 550.0)]),
    ("hip", "hip", [("front", 2, 2, 50.0, 55.0, 530.0), ("back", 2, 2, 50.0, 55.0, 530.0)]),
    ("thigh", "thigh", [("front", 7, 2, 30.0, 55.0, 645.0), ("back", 7, 2, 30.0, 55.0, 645.0)]),
])


def make_robovie():
    channels, taxels, part_groups = [], [], []
    side_members = {"front": [], "back": []}
    for part_id, part_name, blocks in ROBOVIE_PARTS:
        members = []
        for side, rows, columns, film, centre_x, top in blocks:
            pitch = film + ROBOVIE_FILM_GAP_MM
            block_width = columns * pitch - ROBOVIE_FILM_GAP_MM
            offset = ROBOVIE_BACK_OFFSET_MM if side == "back" else 0.0
            for row in range(rows):
                for column in range(columns):
                    number = len(taxels) + 1
                    name = f"s{number:03d}"
                    channels.append({"name": name, "unit": "counts", "modality": "piezo"})
                    x = offset + centre_x - block_width / 2 + film / 2 + column * pitch
                    y = top + film / 2 + row * pitch
                    taxels.append(taxel(number, name, part_id, x, y, film, film, film * film,
                                        "rect", {"piezo": name}))
                    members.append(number)
                    side_members[side].append(number)
        part_groups.append(group(part_id, "body-part", part_name, members))
    assert len(taxels) == 274, len(taxels)
    side_of = {number: side for side, numbers in side_members.items() for number in numbers}
    assert_no_overlap(taxels, lambda entry: side_of[entry["id"]])
    side_groups = [
        group("front", "side", "front view", side_members["front"]),
        group("back", "side", "back view", side_members["back"]),
    ]
    counts = ", ".join(f"{part['id']} {len(part['taxels'])}" for part in part_groups)
    description = (
        "Robovie-IIF child-sized robot with 274 PVDF piezo films (3x3 or 5x5 cm) in soft silicone "
        "skin (paper 003), 16-bit, 100 Hz. The paper names sensors by body part but gives neither "
        "their positions (only its Fig. 4) nor per-part counts: the distribution and placement "
        "here are ours (" + counts + "). Films are numbered part by part so adjacent films have "
        "close numbers, as in the paper. Map: front view on the left (the robot's right on the "
        "map's left), back view on the right (seen from behind); area = film size squared (mm^2). "
        "Classes are the 15 scenario stages of Table I, in order."
    )
    classes = ["Hello.", "Let's shake hands.", "Nice to meet you.", "What's your name?",
               "Where are you from?", "Let's play!", "Do you think I'm cute?",
               "I wish you'd pat me on the head", "Whee!", "I want to play more.", "Tickle me.",
               "That tickles!", "Thanks", "Give me a hug.", "Bye-bye!"]
    return layout(
        "robovie", "Robovie-IIF piezo skin (274 films)", description, 100.0, ["piezo"],
        {"modality": "piezo", "min": 0.0, "max": 32767.0}, channels, taxels,
        part_groups + side_groups, ["body-part", "side"], classes)


# ---- flux -----------------------------------------------------------------------------------------
# Paper 004: two sensing layers of conductive silicone serpentines, mutually orthogonal. One
# serpentine is 55 mm long and 14 mm wide (4 lines of 2 mm with 2 mm spaces); 4 per layer, read at
# 1 kHz with 10 bits. Top layer (x1..x4) = zones 1..4 side by side along x, each stripe running
# along y; bottom layer (y1..y4) orthogonal, stripes running along x. On the map the top layer is
# drawn above the bottom layer so both are visible. Channel order per spec 5.4:
# [top 1-4, top sum, bottom 1-4, bottom sum]; the sums are virtual and have no taxel.
FLUX_LENGTH_MM = 55.0
FLUX_WIDTH_MM = 14.0
FLUX_LAYER_GAP_MM = 15.0
FLUX_STRIPE_GAP_MM = 1.0  # on the map only, so neighbouring stripes can be told apart


def make_flux():
    channels, taxels = [], []
    for layer, prefix in (("top", "x"), ("bottom", "y")):
        for stripe in range(1, 5):
            channels.append({"name": f"{prefix}{stripe}", "unit": "counts",
                             "modality": "resistance"})
        channels.append({"name": f"{prefix}_sum", "unit": "counts", "modality": "resistance"})
    area = FLUX_LENGTH_MM * FLUX_WIDTH_MM
    pitch = FLUX_WIDTH_MM + FLUX_STRIPE_GAP_MM
    layer_span = 4 * pitch - FLUX_STRIPE_GAP_MM
    bottom_top = FLUX_LENGTH_MM + FLUX_LAYER_GAP_MM
    for stripe in range(1, 5):
        x = FLUX_WIDTH_MM / 2 + (stripe - 1) * pitch
        taxels.append(taxel(stripe, f"x{stripe}", "top layer", x, FLUX_LENGTH_MM / 2,
                            FLUX_WIDTH_MM, FLUX_LENGTH_MM, area, "stripe",
                            {"resistance": f"x{stripe}"}))
    for stripe in range(1, 5):
        y = bottom_top + FLUX_WIDTH_MM / 2 + (stripe - 1) * pitch
        taxels.append(taxel(4 + stripe, f"y{stripe}", "bottom layer", layer_span / 2, y,
                            FLUX_LENGTH_MM, FLUX_WIDTH_MM, area, "stripe",
                            {"resistance": f"y{stripe}"}))
    assert_no_overlap(taxels, lambda entry: entry["body_part"])
    groups = [
        group("top", "layer", "top layer (x, zones 1-4)", [1, 2, 3, 4]),
        group("bottom", "layer", "bottom layer (y, orthogonal)", [5, 6, 7, 8]),
    ] + [group(f"zone{zone}", "zone", f"zone {zone}", [zone]) for zone in range(1, 5)]
    description = (
        "Soft silicone touch sensor with two orthogonal layers of 4 piezo-resistive serpentines "
        "(paper 004), 10-bit, 1 kHz. Each serpentine is 55 mm long and 14 mm wide (4 lines of 2 mm, "
        "2 mm apart); the top layer's stripes x1..x4 are zones 1..4 along x, the bottom layer's "
        "y1..y4 run orthogonally. The map draws the top layer above the bottom layer, stripes 1 mm "
        "apart so they can be told apart. Channels "
        "per spec 5.4: x1..x4, x_sum, y1..y4, y_sum; the sums are virtual (sum of normalised "
        "deviations) and have no taxel. Classes: touch1..touch4 = touch on zone 1..4, "
        "caress14 = caress from zone 1 to 4, caress41 = caress from zone 4 to 1."
    )
    return layout(
        "flux", "Silicone tactile flux sensor (2 x 4 serpentines)", description, 1000.0,
        ["resistance"], {"modality": "resistance", "min": 0.0, "max": 1023.0}, channels, taxels,
        groups, ["layer", "zone"],
        ["touch1", "touch2", "touch3", "touch4", "caress14", "caress41"])


def to_text(layout_json):
    """One key per line, one channel / taxel / group per line: readable and diff-friendly."""
    def compact(value):
        return json.dumps(value, ensure_ascii=False, separators=(", ", ": "))

    lines = []
    for key, value in layout_json.items():
        if isinstance(value, list) and value and isinstance(value[0], dict):
            entries = ",\n".join("  " + compact(entry) for entry in value)
            lines.append(f"  {compact(key)}: [\n{entries}\n  ]")
        else:
            lines.append(f"  {compact(key)}: {compact(value)}")
    return "{\n" + ",\n".join(lines) + "\n}\n"


def write(layout_json):
    os.makedirs(LAYOUT_DIR, exist_ok=True)
    path = os.path.join(LAYOUT_DIR, layout_json["id"] + ".json")
    temporary = path + ".tmp"
    with open(temporary, "w", encoding="utf-8") as stream:
        stream.write(to_text(layout_json))
    os.replace(temporary, path)
    print(f"{os.path.relpath(path)}: {len(layout_json['taxels'])} taxels, "
          f"{len(layout_json['channels'])} channels")


def main():
    for make in (make_nao, make_tsa, make_fur, make_robovie, make_flux):
        write(make())


if __name__ == "__main__":
    main()
