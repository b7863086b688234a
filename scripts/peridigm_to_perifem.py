#!/usr/bin/env python3
"""Translate a Peridigm input deck (YAML, or the XML parameter list) into a perifem deck.

    python3 scripts/peridigm_to_perifem.py PERIDIGM_DECK OUT.yaml

What is translated: the discretization (Text File: Peridigm's x y z block_id volume points, with
node-set text files; Exodus: HEX8, TET4 and SPHERE blocks with the file's node sets), the
materials (Elastic -> lps, Elastic Plastic -> elastic_plastic, Elastic Correspondence ->
correspondence with Littlewood's stiffness hourglass control), the critical-stretch damage
model, the blocks (one perifem body for the blocks of one material model, horizon and damage
model, its materials by block, so that bonds cross the blocks as in Peridigm; separate bodies
otherwise, as said on stderr), short-range-force contact, initial velocities, prescribed
displacements and velocities, the explicit (Verlet) or quasi-static solver, and the output file
and frequency. Every key that is not translated is named on stderr, with the reason:
a key that changes the model (an unknown material, a second solver) stops the translation
(exit 2, nothing written); one that only changes output or bookkeeping is listed as left out
(exit 0). Paths in the written deck are relative to its folder. The input is never overwritten.
"""
import argparse
import os
import re
import sys
import xml.etree.ElementTree as ET

import yaml


class Untranslatable(Exception):
    pass


def read_xml(path):
    """Peridigm's XML parameter list as nested dicts."""
    def params(node):
        out = {}
        for child in node:
            name = child.get("name")
            if child.tag == "ParameterList":
                out[name] = params(child)
            elif child.tag == "Parameter":
                kind, value = child.get("type", "string"), child.get("value", "")
                if kind in ("double", "float"):
                    value = float(value)
                elif kind == "int":
                    value = int(value)
                elif kind == "bool":
                    value = value.strip().lower() in ("true", "1", "yes")
                out[name] = value
        return out
    root = ET.parse(path).getroot()
    return params(root)


def read_deck(path):
    with open(path) as f:
        text = f.read()
    if text.lstrip().startswith("<"):
        deck = read_xml(path)
    else:
        deck = yaml.safe_load(text)
        deck = deck.get("Peridigm", deck) if isinstance(deck, dict) else None
    if not isinstance(deck, dict):
        raise Untranslatable(f"{path}: not a Peridigm parameter list (YAML with a 'Peridigm' mapping, or XML)")
    return deck


def name_of(text):
    """A Peridigm name ("Disk Material") as a perifem name (disk_material)."""
    return re.sub(r"[^0-9A-Za-z_]+", "_", str(text).strip()).strip("_").lower() or "unnamed"


def expression(value):
    """A Peridigm function (muParser or RTCompiler) as a perifem expression: numbers and
    muParser text pass; 'if(c){ value = a; } else { value = b; }' becomes '(c) ? (a) : (b)'."""
    text = str(value).replace("\\{", "{").replace("\\}", "}").strip()
    m = re.fullmatch(r"if\s*\((.*)\)\s*\{\s*value\s*=\s*(.*?);\s*\}\s*else\s*\{\s*value\s*=\s*(.*?);\s*\}", text, re.S)
    if m:
        return f"({m.group(1).strip()}) ? ({m.group(2).strip()}) : ({m.group(3).strip()})"
    if "value" in text or "{" in text:
        raise Untranslatable(f"the function '{text}' (only muParser text and if/else of one 'value =' each)")
    return text


class Translator:
    def __init__(self, deck, deck_dir, out_dir):
        self.p, self.deck_dir, self.out_dir = deck, deck_dir, out_dir
        self.left_out = []  # (key, why)
        self.notes = []  # how the blocks became bodies
        self.out = {"title": "translated from Peridigm"}

    def leave(self, key, why):
        self.left_out.append((key, why))

    def path(self, name):
        """A file of the Peridigm deck, relative to the written deck's folder."""
        full = os.path.normpath(os.path.join(self.deck_dir, name))
        if not os.path.exists(full):
            raise Untranslatable(f"the file '{name}' ({full}) does not exist")
        return os.path.relpath(full, self.out_dir)

    # ---- materials and damage -------------------------------------------------------
    def material(self, key, m):
        model = m.get("Material Model")
        out = {"density": m["Density"]}
        moduli = {"bulk_modulus": m.get("Bulk Modulus"), "shear_modulus": m.get("Shear Modulus")}
        if model == "Elastic":
            out["model"] = "lps"
        elif model in ("Elastic Plastic", "Elastic Plastic Hardening"):
            out["model"], out["yield_stress"] = "elastic_plastic", m["Yield Stress"]
            if model.endswith("Hardening"):
                out["hardening_modulus"] = m.get("Hardening Modulus", 0.0)
                self.leave(f"Materials.{key}.Material Model", "perifem's linear hardening is not Peridigm's "
                           "(docs/theory/materials.md, 'Hardening'): the translation uses perifem's")
        elif model == "Elastic Correspondence":
            out["model"] = "elastic"
        else:
            raise Untranslatable(f"Materials.{key}.Material Model: '{model}' (translated: Elastic, Elastic Plastic, "
                                 "Elastic Plastic Hardening, Elastic Correspondence)")
        out.update({k: v for k, v in moduli.items() if v is not None})
        done = {"Material Model", "Density", "Bulk Modulus", "Shear Modulus", "Yield Stress", "Hardening Modulus",
                "Hourglass Coefficient", "Influence Function"}
        for k in m:
            if k in done:
                continue
            if k in ("Apply Shear Correction Factor", "Apply Automatic Differentiation Jacobian", "Verbose"):
                self.leave(f"Materials.{key}.{k}", "no perifem counterpart (bookkeeping of Peridigm's)")
            else:
                raise Untranslatable(f"Materials.{key}.{k} (a material key perifem does not translate)")
        return out

    def influence(self, key, m):
        f = m.get("Influence Function", "One")
        table = {"One": "constant", "1/r": "inverse_distance", "Gaussian": "gaussian"}
        if f not in table:
            raise Untranslatable(f"Materials.{key}.Influence Function: '{f}' (translated: {', '.join(table)})")
        return table[f]

    def damage(self, key):
        d = self.p.get("Damage Models", {}).get(key)
        if d is None:
            raise Untranslatable(f"Damage Models.{key}: named by a block but not defined")
        if d.get("Damage Model") != "Critical Stretch":
            raise Untranslatable(f"Damage Models.{key}.Damage Model: '{d.get('Damage Model')}' (translated: Critical Stretch)")
        for k in d:
            if k not in ("Damage Model", "Critical Stretch"):
                raise Untranslatable(f"Damage Models.{key}.{k} (not translated)")
        return {"law": "critical_stretch", "critical_stretch": d["Critical Stretch"]}

    # ---- discretization and blocks --------------------------------------------------
    def text_blocks(self, mesh):
        """Block id of every point of a text discretization (1-based point order)."""
        ids = []
        with open(os.path.join(self.deck_dir, mesh)) as f:
            for line in f:
                cols = line.split("#")[0].split()
                if cols:
                    ids.append(int(float(cols[3])))
        return ids

    def node_set_files(self):
        """Boundary Conditions' node-set definitions: {Peridigm name: file}."""
        sets = {}
        for k, v in self.p.get("Boundary Conditions", {}).items():
            if isinstance(v, dict):
                continue
            files = str(v).split()
            if len(files) != 1 or not os.path.exists(os.path.join(self.deck_dir, files[0])):
                raise Untranslatable(f"Boundary Conditions.{k}: '{v}' (a node set is translated from a text file)")
            sets[k] = files[0]
        return sets

    def block_entry(self, key, b):
        """One entry of Blocks: its blocks, material, and the body it would make on its own."""
        mkey = b["Material"]
        m = self.p.get("Materials", {}).get(mkey)
        if m is None:
            raise Untranslatable(f"Blocks.{key}.Material: '{mkey}' is not under Materials")
        for k in b:
            if k not in ("Block Names", "Material", "Horizon", "Damage Model"):
                raise Untranslatable(f"Blocks.{key}.{k} (not translated)")
        material = self.material(mkey, m)
        body = {"name": name_of(key), "material": name_of(mkey), "horizon": b["Horizon"]}
        inf = self.influence(mkey, m)
        if inf != "constant":
            body["influence"] = inf
        if m.get("Material Model") == "Elastic Correspondence":
            body["hourglass"] = {"type": "stiffness", "coefficient": m.get("Hourglass Coefficient", 0.0)}
        if "Damage Model" in b:
            body["damage"] = self.damage(b["Damage Model"])
        return str(b["Block Names"]).split(), name_of(mkey), material, body

    def contact_blocks(self):
        """The blocks a contact interaction names: each stays a body of its own."""
        inter = (self.p.get("Contact") or {}).get("Interactions", {})
        return {i.get(k) for i in inter.values() if isinstance(i, dict) for k in ("First Block", "Second Block")}

    def groups(self, entries):
        """Peridigm bonds the points of one discretization across its blocks; perifem bonds the points
        of one body. The entries of one model (material model, influence, hourglass control), horizon
        and damage model become one body, its materials by block; the others stay apart, as said."""
        apart = self.contact_blocks()
        groups = []
        for e in entries:
            blocks, _, material, body = e
            same = (material["model"], body.get("influence"), body.get("hourglass"), body["horizon"], body.get("damage"))
            g = next((g for g in groups if g[0] == same and not apart & set(blocks) and not apart & g[2]), None)
            if g is None:
                groups.append((same, [e], set(blocks)))
            else:
                g[1].append(e)
                g[2].update(blocks)
        if len(groups) > 1:
            parts = [f"{', '.join(b for e in g[1] for b in e[0])} (body '{g[1][0][3]['name']}')" for g in groups]
            self.notes.append("Blocks " + "; ".join(parts) + ": separate bodies (their material model, horizon or "
                              "damage model differ, or a contact interaction names them); no bond joins two bodies, "
                              "where Peridigm bonds points of different blocks within a horizon")
        return [g[1] for g in groups]

    def merged_body(self, group):
        """One body of a group of Blocks entries: the first entry's, with a material_regions entry per
        block when the blocks' materials differ."""
        body = dict(group[0][3])
        blocks = [blk for e in group for blk in e[0]]
        if len({e[1] for e in group}) > 1:
            body["material_regions"] = [{"block": self.block_key(blk), "material": e[1]} for e in group for blk in e[0]]
        if len(group) > 1:
            self.notes.append(f"Blocks: {', '.join(blocks)}: one body '{body['name']}' (one model, horizon and "
                              "damage model; bonds cross the blocks, as in Peridigm)")
        return blocks, body

    def block_key(self, name):
        """A block as material_regions names it: a text file's id (block_<id>), an Exodus block's name."""
        m = re.fullmatch(r"block_(\d+)", name)
        return int(m.group(1)) if self.kind == "Text File" and m else name

    def bodies(self):
        disc = self.p.get("Discretization", {})
        kind, mesh = disc.get("Type"), disc.get("Input Mesh File")
        for k in disc:
            if k not in ("Type", "Input Mesh File"):
                self.leave(f"Discretization.{k}", "not translated (perifem reads the discretization as it is)")
        if kind not in ("Text File", "Exodus"):
            raise Untranslatable(f"Discretization.Type: '{kind}' (translated: Text File, Exodus)")
        self.kind, self.sets = kind, self.node_set_files() if kind == "Text File" else {}
        self.set_name = {k: os.path.splitext(os.path.basename(f))[0] for k, f in self.sets.items()}
        point_blocks = self.text_blocks(mesh) if kind == "Text File" else None
        entries = [self.block_entry(key, b) for key, b in self.p.get("Blocks", {}).items()]
        if not entries:
            raise Untranslatable("Blocks: no block")
        materials = {e[1]: e[2] for e in entries}
        bodies = []
        for group in self.groups(entries):
            blocks, body = self.merged_body(group)
            if kind == "Exodus":
                g = {"shape": "exodus", "file": self.path(mesh), "blocks": blocks}
            else:
                g = self.text_geometry(body["name"], mesh, blocks, point_blocks)
            first = ("name", "material", "material_regions", "horizon")
            body = {**{k: body[k] for k in first if k in body}, "geometry": g,
                    **{k: v for k, v in body.items() if k not in first}}
            bodies.append((blocks, body))
        self.out["materials"], self.blocks = materials, bodies
        self.out["bodies"] = [b for _, b in bodies]

    def text_geometry(self, key, mesh, blocks, point_blocks):
        ids = []
        for name in blocks:
            m = re.fullmatch(r"block_(\d+)", name)
            if not m:
                raise Untranslatable(f"Blocks: '{name}' of body '{key}' (a text discretization's blocks are block_<id>)")
            ids.append(int(m.group(1)))
        g = {"shape": "points_file", "file": self.path(mesh), "columns": "peridigm"}
        present = set(point_blocks)
        if len(ids) == 1 and present != {ids[0]}:
            g["block"] = ids[0]
        elif set(ids) != present:
            raise Untranslatable(f"Blocks: {blocks} (body '{key}') is part of the file's blocks {sorted(present)}: "
                                 "perifem takes one block of a text file, or all of them, per body")
        if self.sets:
            g["node_set_files"] = [self.path(f) for f in self.sets.values()]
        return g

    # ---- boundary conditions --------------------------------------------------------
    def set_of(self, key, bc):
        name = bc.get("Node Set")
        if self.kind == "Text File":
            if name not in self.set_name:
                raise Untranslatable(f"Boundary Conditions.{key}.Node Set: '{name}' is not defined by a file")
            return self.set_name[name]
        return name

    def boundary_conditions(self):
        initial, prescribed = {}, {}
        kinds = {"Initial Velocity": None, "Prescribed Displacement": "displacement",
                 "Prescribed Velocity": "velocity"}
        for key, bc in self.p.get("Boundary Conditions", {}).items():
            if not isinstance(bc, dict):
                continue
            t = bc.get("Type")
            if t not in kinds:
                raise Untranslatable(f"Boundary Conditions.{key}.Type: '{t}' (translated: {', '.join(kinds)})")
            c = "xyz".index(str(bc["Coordinate"]).strip().lower())
            s = self.set_of(key, bc)
            value = expression(bc["Value"])
            if t == "Initial Velocity":
                initial.setdefault(s, ["0", "0", "0"])[c] = value
            else:
                entry = prescribed.setdefault((s, kinds[t]), ["free", "free", "free"])
                if entry[c] != "free":
                    raise Untranslatable(f"Boundary Conditions.{key}: a second condition on coordinate {'xyz'[c]} of '{s}'")
                entry[c] = value
        if len(initial) > 1:
            raise Untranslatable(f"Boundary Conditions: initial velocities on several node sets {sorted(initial)} "
                                 "(perifem gives a body its initial velocity on one node set)")
        for s, v in initial.items():
            for body in self.out["bodies"]:
                body["initial_velocity"], body["initial_velocity_set"] = list(v), s
        bcs = [{"name": name_of(f"{s}_{kind}"), "region": {"shape": "node_set", "set": s}, kind: v}
               for (s, kind), v in prescribed.items()]
        if bcs:
            self.out["boundary_conditions"] = bcs

    # ---- contact, solver, output ----------------------------------------------------
    def contact(self):
        c = self.p.get("Contact")
        if not c:
            return
        for k in c:
            if k in ("Search Radius", "Search Frequency"):
                self.leave(f"Contact.{k}", "perifem rebuilds its search when a point has moved half of contact.skin")
            elif k not in ("Models", "Interactions"):
                raise Untranslatable(f"Contact.{k} (not translated)")
        body_of = {blk: body["name"] for blocks, body in self.blocks for blk in blocks}
        pairs = []
        for key, i in c.get("Interactions", {}).items():
            model = c.get("Models", {}).get(i["Contact Model"], {})
            if model.get("Contact Model") != "Short Range Force":
                raise Untranslatable(f"Contact.Models.{i['Contact Model']}: '{model.get('Contact Model')}' "
                                     "(translated: Short Range Force)")
            a, b = (body_of.get(i[k]) for k in ("First Block", "Second Block"))
            if a is None or b is None:
                raise Untranslatable(f"Contact.Interactions.{key}: a block that is no block's")
            pair = {"bodies": [a, b], "radius": model["Contact Radius"], "spring_constant": model["Spring Constant"]}
            if model.get("Friction Coefficient"):
                pair["friction"] = model["Friction Coefficient"]
            pairs.append(pair)
        if pairs:
            self.out["contact"] = {"pairs": pairs}

    def solver(self):
        solvers = [k for k in self.p if re.fullmatch(r"Solver\d*", k)]
        if len(solvers) != 1:
            raise Untranslatable(f"{' and '.join(solvers) or 'Solver'}: perifem runs one solver per deck "
                                 "(split the run in two decks, the second restarting from the first's checkpoint)")
        s = self.p[solvers[0]]
        if float(s.get("Initial Time", 0.0)) != 0.0:
            raise Untranslatable(f"{solvers[0]}.Initial Time: {s['Initial Time']} (perifem starts at 0)")
        time = {"final_time": s["Final Time"]}
        if "Verlet" in s:
            v = s["Verlet"]
            time["safety_factor"] = v.get("Safety Factor", 1.0)
            if "Fixed dt" in v:
                time["dt"] = v["Fixed dt"]
        elif "QuasiStatic" in s:
            q = s["QuasiStatic"]
            self.out["solver"] = {"type": "quasi_static", "load_steps": q["Number of Load Steps"]}
            for k in q:
                if k != "Number of Load Steps":
                    self.leave(f"{solvers[0]}.QuasiStatic.{k}", "Peridigm's Newton solver; perifem's relaxation has "
                               "its own relative tolerance (solver.tolerance)")
        else:
            raise Untranslatable(f"{solvers[0]}: translated are Verlet and QuasiStatic")
        for k in s:
            if k not in ("Initial Time", "Final Time", "Verlet", "QuasiStatic"):
                self.leave(f"{solvers[0]}.{k}", "not translated")
        self.out["time"] = time

    def output(self, out_path):
        outputs = [k for k in self.p if re.fullmatch(r"Output\w*", k)]
        section = {}
        point_vars = {"Displacement", "Velocity", "Force", "Damage"}
        for k in outputs:
            o = self.p[k]
            names = {v for v, on in o.get("Output Variables", {}).items() if on}
            if names and names <= {v for v in names if v.startswith("Global_")}:
                section["history_interval"] = int(o.get("Output Frequency", 1))
                continue
            stem = os.path.splitext(os.path.basename(out_path))[0]
            section["file"] = f"{name_of(o.get('Output Filename', stem))}.e"
            section["interval"] = int(o.get("Output Frequency", 1))
            other = sorted(names - point_vars)
            if other:
                self.leave(f"{k}.Output Variables", "perifem writes its own fields (displacement, velocity, force, "
                           f"damage, ...); not these: {', '.join(other)}")
        if section:
            self.out["output"] = section

    def translate(self, out_path):
        known = {"Discretization", "Materials", "Damage Models", "Blocks", "Contact", "Boundary Conditions"}
        for k in self.p:
            if k in known or re.fullmatch(r"(Solver|Output)\w*", k):
                continue
            if k in ("Verbose",):
                self.leave(k, "not translated (perifem's --quiet)")
            elif k == "Compute Class Parameters":
                self.leave(k, "perifem's history holds each boundary condition's reaction and output.probes average "
                           "regions; these computes are not translated")
            else:
                raise Untranslatable(f"{k} (a section perifem does not translate)")
        self.bodies()
        self.boundary_conditions()
        self.contact()
        self.solver()
        self.output(out_path)
        return self.out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("deck", help="Peridigm input deck (.yaml or .xml)")
    ap.add_argument("out", help="the perifem deck to write (.yaml)")
    a = ap.parse_args()
    if os.path.exists(a.out) and os.path.samefile(a.out, a.deck):
        sys.exit(f"peridigm_to_perifem: error: '{a.out}' is the input deck; name another file")
    out_dir = os.path.dirname(os.path.abspath(a.out))
    try:
        t = Translator(read_deck(a.deck), os.path.dirname(os.path.abspath(a.deck)), out_dir)
        deck = t.translate(a.out)
    except Untranslatable as e:
        print(f"peridigm_to_perifem: error: {a.deck}: cannot translate {e}; nothing written", file=sys.stderr)
        sys.exit(2)
    except (KeyError, ValueError, TypeError, OSError, yaml.YAMLError, ET.ParseError) as e:
        print(f"peridigm_to_perifem: error: {a.deck}: {type(e).__name__}: {e}; nothing written", file=sys.stderr)
        sys.exit(2)
    for key, why in t.left_out:
        print(f"peridigm_to_perifem: left out: {key}: {why}", file=sys.stderr)
    for note in t.notes:
        print(f"peridigm_to_perifem: note: {note}", file=sys.stderr)
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        f.write(f"# translated from {os.path.relpath(os.path.abspath(a.deck), out_dir)} by scripts/peridigm_to_perifem.py\n")
        for note in t.notes:
            f.write(f"# {note}\n")
        yaml.safe_dump(deck, f, sort_keys=False, default_flow_style=None, width=110)
    os.replace(tmp, a.out)
    print(f"wrote {a.out}: {len(deck['bodies'])} bod{'y' if len(deck['bodies']) == 1 else 'ies'}, "
          f"{len(t.left_out)} key(s) left out")


if __name__ == "__main__":
    main()
