#!/usr/bin/python3
"""A corpus of bad inputs, generated here from a small 2D scene: parameter files
that include themselves, devices, directories and FIFOs; boundary functions
that give NaN or inf at some time, or whose constants shadow a variable; broken
Gmsh .msh files (empty, truncated, unknown version or element type, missing
nodes, NaN coordinates, counts larger than the file, random bytes, binary);
.geo files that exit, loop forever, mesh far too finely or do not parse;
material, contact and load-stepping values outside their range; a contact zone
radius that holds no face of a coarse mesh; and a misspelt subsection after an
include or inside an included file (named at its own file and line).

Each case must end within its time limit with exit code 1 and a message that
names the file or entry (the `expect` text of the case), without a crash trace
(signal, abort, uncaught exception), and leave no NaN in the files it wrote.
Prints the tally: cases, clean errors, crashes, hangs, accepted."""
import os
import random
import re
import shutil
import subprocess
import sys
import sltest

executable, workdir = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
shutil.rmtree(workdir, ignore_errors=True)
os.makedirs(workdir)
check = sltest.Checker()

SCENE = """set Dimension = 2
subsection Geometry
  set Model = block
  subsection block
    set Length = 40
    set Height = 10
    set Subdivisions = 4, 1
    set Global refinements = 1
  end
end
subsection Obstacle
  set Model = plane
  subsection plane
    set Point  = 0, 0
    set Normal = 0, 1
  end
end
""" + sltest.linear_elastic(70000, 0.33) + sltest.coulomb_contact("  set Contact boundary ids = 2\n", 0.3) + """subsection Boundary conditions
  subsection Dirichlet 1
    set Boundary id = 3
    set Components  = x, y
    subsection Displacement
      set Function constants  = d=0.01
      set Function expression = DISPLACEMENT
      set Variable names      = x,y,t
    end
  end
end
subsection Load stepping
  set End time = 1
  set Number of load steps = 4
end
subsection Output
  set Output directory = output
  set Write vtu = false
end
"""
GOOD_DISPLACEMENT = "0.1*d*t; -d*min(2*t, 1)"

# the physical groups of the test meshes: named boundaries and body
PHYSICAL_NAMES = """$PhysicalNames
3
1 1 "bottom"
1 2 "top"
2 3 "block"
$EndPhysicalNames
"""
# a 2 x 1 quadrilateral mesh in Gmsh format 2.2
GOOD_MSH = """$MeshFormat
2.2 0 8
$EndMeshFormat
""" + PHYSICAL_NAMES + """$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
6
1 1 2 1 1 1 2
2 1 2 1 1 2 3
3 1 2 2 2 4 5
4 1 2 2 2 5 6
5 3 2 3 1 1 2 5 4
6 3 2 3 1 2 3 6 5
$EndElements
"""
# the same mesh in format 4.1
GOOD_MSH4 = """$MeshFormat
4.1 0 8
$EndMeshFormat
""" + PHYSICAL_NAMES + """$Entities
0 2 1 0
1 0 0 0 2 0 0 1 1 0
2 0 1 0 2 1 0 1 2 0
1 0 0 0 2 1 0 1 3 0
$EndEntities
$Nodes
1 6 1 6
2 1 0 6
1
2
3
4
5
6
0 0 0
1 0 0
2 0 0
0 1 0
1 1 0
2 1 0
$EndNodes
$Elements
3 6 1 6
1 1 1 2
1 1 2
2 2 3
1 2 1 2
3 4 5
4 5 6
2 1 3 2
5 1 2 5 4
6 2 3 6 5
$EndElements
"""
GMSH_SCENE = SCENE.replace("""  set Model = block
  subsection block
    set Length = 40
    set Height = 10
    set Subdivisions = 4, 1
    set Global refinements = 1
  end""", """  set Model = gmsh
  subsection gmsh
    set Mesh file = MESH
    set Meshing time limit = 5
    set Meshing memory limit = 1000
  end""").replace("set Contact boundary ids = 2", "set Contact boundary ids = bottom") \
    .replace("set Boundary id = 3", "set Boundary id = top")
BLOCK_GEO = """Point(1) = {0, 0, 0}; Point(2) = {NX, 0, 0}; Point(3) = {NX, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1; Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1}; Recombine Surface{1};
Physical Curve("bottom") = {1}; Physical Curve("top") = {3}; Physical Surface("block") = {1};
"""


def files_with_nan(directory):
    """The CSV files under directory with a NaN or infinite value."""
    token = re.compile(r"(^|[,\s])[-+]?(nan|inf)", re.IGNORECASE)
    return [os.path.join(top, name) for top, _, names in os.walk(directory) for name in names
            if name.endswith(".csv") and token.search(open(os.path.join(top, name)).read())]


def scene(displacement=GOOD_DISPLACEMENT, settings=()):
    text = SCENE.replace("DISPLACEMENT", displacement)
    return text + "".join(sltest.nested_set(path, value) for path, value in settings)


def msh_case(name, mesh_text, expect):
    """A case whose mesh file is mesh_text (str or bytes)."""
    def prepare(directory):
        mode = "wb" if isinstance(mesh_text, bytes) else "w"
        with open(os.path.join(directory, name), mode) as f:
            f.write(mesh_text)
        return GMSH_SCENE.replace("DISPLACEMENT", GOOD_DISPLACEMENT).replace("MESH", name)
    return prepare, expect


def files_case(files, prm_name="input.prm", special=None, expect=""):
    """A case with extra files {name: text}; special(directory) makes devices, FIFOs, directories."""
    def prepare(directory):
        for name, text in files.items():
            with open(os.path.join(directory, name), "w") as f:
                f.write(text)
        if special:
            special(directory)
        return None  # the case writes its own input
    return prepare, expect, prm_name


def make_fifo(directory):
    os.mkfifo(os.path.join(directory, "fifo.prm"))


def make_directory(directory):
    os.makedirs(os.path.join(directory, "folder.prm"), exist_ok=True)


random.seed(14)
random_bytes = bytes(random.getrandbits(8) for _ in range(3000))
lines = GOOD_MSH.splitlines(keepends=True)

# (name, prepare, expected text in the message, [input file name])
cases = []


def text_case(name, text, expect):
    cases.append((name, lambda directory, text=text: text, expect, "input.prm"))


# --- the parameter file
for name, files, special, prm, expect in (
        ("include itself", {"input.prm": "include input.prm\n"}, None, "input.prm", "includes itself"),
        ("include cycle", {"input.prm": "include b.prm\n", "b.prm": "# b\ninclude input.prm\n"}, None,
         "input.prm", "includes itself"),
        ("include /dev/zero", {"input.prm": "include /dev/zero\n"}, None, "input.prm", "/dev/zero"),
        ("include a directory", {"input.prm": "include folder.prm\n"}, make_directory, "input.prm",
         "folder.prm' is a directory"),
        ("include a FIFO", {"input.prm": "include fifo.prm\n"}, make_fifo, "input.prm", "fifo.prm"),
        ("include a missing file", {"input.prm": "include nowhere.prm\n"}, None, "input.prm",
         "nowhere.prm' does not exist"),
        ("include without a name", {"input.prm": "include\n"}, None, "input.prm", "without a file name"),
        ("input is a directory", {}, make_directory, "folder.prm", "is a directory"),
        ("input is a FIFO", {}, make_fifo, "fifo.prm", "not a regular file"),
        ("input is /dev/null", {}, None, "/dev/null", "not a regular file"),
        ("input is empty", {"input.prm": ""}, None, "input.prm", "sets no parameter"),
        ("input is binary", {}, None, "random.prm", "NUL bytes"),
        ("input is missing", {}, None, "missing.prm", "does not exist"),
        # NUL bytes: the file and the line of the first
        ("a NUL byte on line 3", {"input.prm": "set Dimension = 2\n# a comment\nset Dim\0ension = 2\n"},
         None, "input.prm", "'input.prm' line 3: The parameter file contains NUL bytes"),
        ("a NUL byte in an included file",
         {"input.prm": "include b.prm\n", "b.prm": "set Dimension = 2\n\0\n"}, None, "input.prm",
         "'b.prm' line 2: The included file contains NUL bytes")):
    prepare, expect, prm = files_case(files, prm, special, expect)
    cases.append((name, prepare, expect, prm))

# --- boundary functions: NaN or inf at some time or point, constants that shadow variables
for name, displacement, expect in (
        ("0/0 after t = 0.5", "if(t < 0.5, 0, 0/0); -d*t", "gives"),
        ("sqrt of a negative number", "0; -d*sqrt(0.6 - t)", "gives"),
        ("division by zero at t = 0.5", "0; -d*t/(t - 0.5)", "gives"),
        ("NaN at one point", "0; -d*t*sqrt(x - 20)", "gives"),
        ("an undefined name", "0; -dd*t", "Dirichlet 1/Displacement"),
        ("a nan token", "0; nan", "Dirichlet 1/Displacement"),
        ("one component", "-d*t", "Dirichlet 1/Displacement")):
    text_case(name, scene(displacement), expect)
text_case("a constant named t", scene().replace("set Function constants  = d=0.01",
                                                "set Function constants  = d=0.01, t=1"), "'t' is also a variable")
text_case("a constant named x", scene().replace("set Function constants  = d=0.01",
                                                "set Function constants  = x=0.01"), "'x' is also a variable")
text_case("a constant without a value", scene().replace("set Function constants  = d=0.01",
                                                        "set Function constants  = d"), "Dirichlet 1/Displacement")

# --- values out of range
for name, path, value, expect in (
        ("E = nan", "Material/linear elastic/Young's modulus", "nan", "Young's modulus"),
        ("E = -1", "Material/linear elastic/Young's modulus", "-1", "Young's modulus"),
        ("nu = 0.5", "Material/linear elastic/Poisson's ratio", "0.5", "Poisson's ratio"),
        ("nu = inf", "Material/linear elastic/Poisson's ratio", "inf", "Poisson's ratio"),
        ("mu = nan", "Contact/Friction law/Coulomb/Friction coefficient", "nan", "Friction coefficient"),
        ("mu = -0.1", "Contact/Friction law/Coulomb/Friction coefficient", "-0.1", "Friction coefficient"),
        ("r_n = nan", "Contact/r_n", "nan", "r_n"),
        ("r_n = 0", "Contact/r_n", "0", "r_n"),
        ("r_t = -1", "Contact/r_t", "-1", "r_t"),
        ("end time = inf", "Load stepping/End time", "inf", "End time"),
        ("end time = 0", "Load stepping/End time", "0", "End time"),
        ("zero load steps", "Load stepping/Number of load steps", "0", "Number of load steps"),
        ("obstacle normal = 0", "Obstacle/plane/Normal", "0, 0", "Normal"),
        ("obstacle point = nan", "Obstacle/plane/Point", "nan, 0", "Point"),
        ("unknown material", "Material/Model", "steel", "Model"),
        ("unknown pair", "Contact/Finite element pair", "Q7/P9", "Finite element pair")):
    text_case(name, scene(settings=[(path, value)]), expect)
# numbers no double holds (denormal, beyond the largest) and integers no id holds: the entry, the
# file and line and the range allowed, no raw "Can't convert", "stoul" or "stoi"
for name, path, value, expect in (
        ("end time = 1e-320", "Load stepping/End time", "1e-320",
         "Load stepping/End time = 1e-320: 1e-320 is smaller in magnitude than the smallest normal double"),
        ("E = 1e-320", "Material/linear elastic/Young's modulus", "1e-320",
         "Material/linear elastic/Young's modulus = 1e-320: 1e-320 is smaller"),
        ("mu = 1e400", "Contact/Friction law/Coulomb/Friction coefficient", "1e400",
         "Contact/Friction law/Coulomb/Friction coefficient = 1e400: 1e400 is larger in magnitude than the largest double"),
        ("obstacle point = 1e-320", "Obstacle/plane/Point", "1e-320, 0", "Obstacle/plane/Point = 1e-320, 0"),
        ("a constant of 1e-320", "Boundary conditions/Dirichlet 1/Displacement/Function constants",
         "d=1e-320", "Boundary conditions/Dirichlet 1/Displacement/Function constants = d=1e-320: 1e-320 is smaller"),
        ("a 23-digit contact boundary id", "Contact/Contact boundary ids", "12345678901234567890123",
         "Contact/Contact boundary ids = 12345678901234567890123: a boundary id is an integer from 0 to"),
        ("a 23-digit Dirichlet boundary id", "Boundary conditions/Dirichlet 1/Boundary id",
         "12345678901234567890123",
         "Boundary conditions/Dirichlet 1/Boundary id = 12345678901234567890123: a boundary id"),
        ("a 23-digit master boundary id", "Contact/Master boundary ids", "12345678901234567890123",
         "Contact/Master boundary ids = 12345678901234567890123: a boundary id"),
        ("a 24-digit refinement count", "Geometry/block/Global refinements", "1" * 24,
         f"Geometry/block/Global refinements = {'1' * 24}: not allowed; the entry takes [Integer range 0...12"),
        ("a 23-digit body", "Material 2/Bodies", "12345678901234567890123",
         "Material 2/Bodies = '12345678901234567890123': the mesh has no body")):
    text = scene(settings=[(path, value)])
    line = text.splitlines().index(f"set {path.split('/')[-1]} = {value}") + 1
    text_case(name, text, f"'input.prm' line {line}: {expect}")
# a range error names the file and the line of its entry
text = scene(settings=[("Load stepping/End time", "-1")])
text_case("end time = -1 with its line", text,
          f"'input.prm' line {text.splitlines().index('set End time = -1') + 1}: Load stepping/End time")
# the entry of a function at fault: its constants, its variable names or its expression
DISPLACEMENT = "Boundary conditions/Dirichlet 1/Displacement"
for name, entry, value, expect in (
        ("a constant that is no number", "Function constants", "d=abc", "Function constants = 'd=abc'"),
        ("a constant without a name", "Function constants", "=0.01", "Function constants = '=0.01'"),
        ("a variable named twice", "Variable names", "x,x,t", "Variable names = 'x,x,t': 'x' is given twice"),
        ("a variable that is no name", "Variable names", "x,2y,t", "Variable names = 'x,2y,t': '2y' is not a name"),
        ("three components", "Function expression", "0; -d*t; 1",
         "Function expression = '0; -d*t; 1': 2 component(s) separated by ';' are needed, got 3"),
        ("an unclosed parenthesis", "Function expression", "0; -d*(t",
         "Function expression = '0; -d*(t': the expression could not be parsed")):
    text_case(name, scene(settings=[(f"{DISPLACEMENT}/{entry}", value)]), f"{DISPLACEMENT}/{expect}")
# the contact zone of a ball: in (0, 2 R], checked when it is read (it was reported as the contact
# surface's missing boundary id)
for name, value in (("zero contact zone radius", "0"), ("negative contact zone radius", "-1"),
                    ("contact zone radius 1e308", "1e308")):
    text_case(name, scene(settings=[("Geometry/Model", "half ball"),
                                    ("Geometry/half ball/Contact zone radius", value)]),
              f"Geometry/half ball/Contact zone radius = {value}: the distance (mm) from the contact "
              "point within which the curved faces form the contact surface must be > 0 and at most "
              "twice the radius")
text_case("two balls' contact zone radius 0", scene(settings=[("Geometry/Model", "two balls"),
                                                              ("Geometry/two balls/Contact zone radius", "0")]),
          "Geometry/two balls/Contact zone radius = 0: the distance")
# a plug-in chosen in more than one place names the subsection the value was written in
ZONE_LEFT = [("Contact/Zone left/Boundary ids", "2"), ("Contact/Complementarity", "pointwise")]
for name, settings, expect in (
        ("mu = -0.1 in a contact zone",
         [("Contact/Zone left/Friction law/Coulomb/Friction coefficient", "-0.1")],
         "Contact/Zone left/Friction law/Coulomb/Friction coefficient must be >= 0"),
        ("s = -1 in a contact zone",
         [("Contact/Zone left/Friction law/Model", "Tresca"),
          ("Contact/Zone left/Friction law/Tresca/Threshold", "-1")],
         "Contact/Zone left/Friction law/Tresca/Threshold must be >= 0")):
    text_case(name, scene(settings=ZONE_LEFT + settings), expect)
for name, model, entry, value in (
        ("E = -1 in a material slot", "linear elastic", "Young's modulus", "-1"),
        ("C10 = 0 in a material slot", "neo-Hookean", "C10", "0"),
        ("a bad hardening curve in a material slot", "J2 plasticity", "Hardening curve", "0:250, 0.1:200")):
    text_case(name, scene(settings=[("Material 2/Bodies", "0"), ("Material 2/Model", model),
                                    (f"Material 2/{model}/{entry}", value)]),
              f"Material 2/{model}/{entry}")
# conditions of one kind are read in ParameterHandler's order of subsections (a name's characters
# outside [A-Za-z0-9] sort as `_` and two hex digits: `aZ` before `a 1` and `a-b`), the order
# in which they have always been applied: the first one refused is `aZ`
text_case("point loads in ParameterHandler's order", scene() + "".join(
    sltest.nested_set(f"Boundary conditions/Point load {name}/Point", "x") for name in ("a 1", "aZ", "a-b")),
          "Point load aZ/Point = 'x'")
# combinations the dual multiplier basis cannot take
DUAL = ("Contact/Finite element pair", "Q1/P1 dual")
text_case("dual pair, pointwise conditions",
          scene(settings=[DUAL, ("Contact/Complementarity", "pointwise")]), "Complementarity = weighted")
text_case("dual pair, nodal quadrature",
          scene(settings=[DUAL, ("Contact/Complementarity", "weighted"),
                          ("Contact/Contact quadrature", "Gauss-Lobatto")]), "Contact quadrature = Gauss")

# boundary conditions: a subsection of no known kind, springs that hold nothing or pull back
SPRING = """subsection Boundary conditions
  subsection Spring side
    set Boundary id = BOUNDARY
    set Stiffness   = STIFFNESS
  end
end
"""
text_case("a Robin subsection", scene() + "subsection Boundary conditions\n  subsection Robin 1\n  end\nend\n",
          "'Spring <name>'")
text_case("a Dirichlet subsection without a name",
          scene() + "subsection Boundary conditions\n  subsection Dirichlet\n  end\nend\n", "'Dirichlet <name>'")
text_case("springs of zero stiffness", scene() + SPRING.replace("BOUNDARY", "0").replace("STIFFNESS", "0, 0"),
          "Spring side/Stiffness")
text_case("springs of negative stiffness",
          scene() + SPRING.replace("BOUNDARY", "0").replace("STIFFNESS", "-1, 0"), "Stiffness")
text_case("springs on a boundary the mesh lacks",
          scene() + SPRING.replace("BOUNDARY", "9").replace("STIFFNESS", "1, 0"), "Spring side/Boundary id")

PLATE = """subsection Boundary conditions
  subsection Rigid plate top
    set Boundary id = 3
    set Components  = COMPONENTS
  end
end
"""
text_case("a rigid plate tying nothing", scene() + PLATE.replace("COMPONENTS", ""), "Rigid plate top/Components")
text_case("a rigid plate where a Dirichlet condition holds",
          scene() + PLATE.replace("COMPONENTS", "y"), "Rigid plate top: its boundary shares nodes with")

text_case("an obstacle motion giving NaN", scene(settings=[("Obstacle/Motion/Function expression",
                                                           "0; if(t < 0.5, 0, 0/0)")]), "Obstacle/Motion")

text_case("two balls touching", scene(settings=[("Geometry/Model", "two balls"),
                                                ("Geometry/two balls/Initial gap", "0")]), "Initial gap")

# --- Gmsh .msh files
for name, mesh, expect in (
        ("empty.msh", "", "is empty"),
        ("truncated.msh", "".join(lines[:19]), "not closed"),
        ("version.msh", GOOD_MSH.replace("2.2 0 8", "9.9 0 8"), "format version 9.9"),
        ("element_type.msh", GOOD_MSH.replace("5 3 2 3 1 1 2 5 4", "5 99 2 3 1 1 2 5 4"), "element type 99"),
        ("missing_node.msh", GOOD_MSH.replace("5 3 2 3 1 1 2 5 4", "5 3 2 3 1 1 2 5 40"), "node 40"),
        ("nan_node.msh", GOOD_MSH.replace("5 1 1 0", "5 nan 1 0"), "line 16"),
        ("inf_node.msh", GOOD_MSH.replace("5 1 1 0", "5 1e999 1 0"), "line 16"),
        ("node_count.msh", GOOD_MSH.replace("$Nodes\n6\n", "$Nodes\n7\n"), "$EndNodes"),
        ("huge_count.msh", GOOD_MSH.replace("$Nodes\n6\n", "$Nodes\n6000000\n"), "larger than the file"),
        ("element_count.msh", GOOD_MSH.replace("$Elements\n6\n", "$Elements\n5\n"), "$EndElements"),
        ("random.msh", random_bytes, "random.msh"),
        ("binary_flag.msh", GOOD_MSH.replace("2.2 0 8", "2.2 1 8"), "binary"),
        ("names_count.msh", GOOD_MSH.replace("$PhysicalNames\n3\n", "$PhysicalNames\n30\n"), "names_count.msh"),
        ("names_quotes.msh", GOOD_MSH.replace('2 3 "block"', "2 3 block"), "physical name"),
        ("no_format.msh", GOOD_MSH.replace("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", ""), "$MeshFormat"),
        ("duplicate_node.msh", GOOD_MSH.replace("6 2 1 0", "5 2 1 0"), "defined twice"),
        ("v4_node_count.msh", GOOD_MSH4.replace("$Nodes\n1 6 1 6", "$Nodes\n1 7 1 7"), "announces 7 nodes"),
        ("v4_missing_node.msh", GOOD_MSH4.replace("5 1 2 5 4", "5 1 2 5 9"), "node 9"),
        ("v4_block_size.msh", GOOD_MSH4.replace("2 1 0 6\n", "2 1 0 60000\n"), "larger than the file"),
        ("mixed_cells.msh", GOOD_MSH.replace("5 3 2 3 1 1 2 5 4", "5 2 2 3 1 1 2 5"), "mixes 1 simplices"),
        ("exit.geo", BLOCK_GEO.replace("NX", "2").replace("NY", "1") + "Exit;\n", "Exit"),
        ("endless.geo", "For i In {1:1e12}\nEndFor\n", "Meshing time limit"),
        ("huge.geo", BLOCK_GEO.replace("NX", "30000").replace("NY", "30000"), "huge.geo"),
        ("syntax.geo", "Point(1) = {0, 0, 0;\n", "could not mesh"),
        ("no_surface.geo", "Point(1) = {0,0,0}; Point(2) = {1,0,0}; Line(1) = {1,2};\n"
         "Physical Curve(\"bottom\") = {1};\n", "no_surface.geo"),
        ("no_groups.geo", re.sub(r"Physical.*\n", "", BLOCK_GEO.replace("NX", "2").replace("NY", "1")),
         "bottom")):
    prepare, expect = msh_case(name, mesh, expect)
    cases.append((name, prepare, expect, "input.prm"))

# the checks of the .msh files accept the good meshes: both formats run and agree
good_runs = []
for name, mesh in (("good.msh", GOOD_MSH), ("good4.msh", GOOD_MSH4)):
    directory = os.path.join(workdir, name.replace(".", "_"))
    os.makedirs(directory)
    prepare, _ = msh_case(name, mesh, "")
    code, log = sltest.run(executable, prepare(directory), directory, expect_success=False)
    check(code == 0, f"{name}: a valid mesh runs (exit code {code})")
    good_runs.append([{k: v for k, v in row.items() if "time" not in k or k == "time"}
                      for row in sltest.read_csv(os.path.join(directory, "output", "statistics.csv"))]
                     if code == 0 else None)
check(good_runs[0] is not None and good_runs[0] == good_runs[1],
      "formats 2.2 and 4.1 of the same mesh give the same statistics (wall time aside)")

# a contact zone radius in (0, 2 R] that holds no face centre of a coarse mesh: the zone's entry,
# its radius, the nearest face centre's distance and what to do (not "no boundary with this id")
text_case("a contact zone holding no face", scene(settings=[
    ("Geometry/Model", "half ball"), ("Geometry/half ball/Global refinements", "0"),
    ("Geometry/half ball/Local refinements", "0"), ("Geometry/half ball/Contact zone radius", "5")]),
          "Contact/Contact boundary ids = 2: the contact zone holds no face of the mesh. Geometry/half "
          "ball/Contact zone radius = 5 mm takes the curved faces whose centre lies within 5 mm of the "
          "contact point (0 0), and on this mesh the nearest face centre is 29.2893 mm from it (faces "
          "of 141.421 mm there). Raise Geometry/half ball/Contact zone radius above 29.2893 mm, or refine")
# a misspelt subsection after an include of a shipped scene, and one inside an included file: the
# file and the line where it is written (it was the line of the expanded text in "file <input string")
SHIPPED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm", "patin_elastic.prm")
included = scene() + "subsection Contactt\n  set r_n = 1\nend\n"
for name, files, expect in (
        ("a misspelt subsection after an include",
         {"input.prm": f"include {SHIPPED}\n# a comment\n\n\nsubsection Contactt\n  set r_n = 1\nend\n"},
         "'input.prm' line 5: There is no such subsection to be entered: Contactt"),
        ("a misspelt subsection in an included file", {"input.prm": "# the scene\ninclude base.prm\n",
                                                       "base.prm": included},
         f"'base.prm' line {included.splitlines().index('subsection Contactt') + 1}: There is no such "
         "subsection to be entered: Contactt")):
    prepare, expect, prm = files_case(files, "input.prm", None, expect)
    cases.append((name, prepare, expect, prm))

CRASH = re.compile(r"Segmentation|Signal:|terminate called|Aborted|core dumped|Stacktrace|\*\*\* Process")
tally = {"clean error": 0, "crash": 0, "hang": 0, "accepted": 0}
for number, (name, prepare, expect, prm_name) in enumerate(cases):
    directory = os.path.join(workdir, f"case{number:03d}")
    os.makedirs(directory)
    with open(os.path.join(directory, "random.prm"), "wb") as f:
        f.write(random_bytes)
    text = prepare(directory)
    if text is not None:
        with open(os.path.join(directory, prm_name), "w") as f:
            f.write(text)
    try:
        result = subprocess.run([executable, prm_name], cwd=directory, env=sltest.MPI_ENV,
                                capture_output=True, text=True, errors="replace", timeout=60)
        code, log = result.returncode, result.stdout + result.stderr
    except subprocess.TimeoutExpired:
        tally["hang"] += 1
        check(False, f"{name}: still running after 60 s")
        continue
    # the child process that meshes a .geo may print its own abort; the run itself must not
    run_log = log if not name.endswith(".geo") else "\n".join(
        line for line in log.splitlines() if "terminate called" not in line and "what():" not in line)
    if code == 0:
        tally["accepted"] += 1
    elif code != 1 or CRASH.search(run_log):
        tally["crash"] += 1
    else:
        tally["clean error"] += 1
    nan_files = files_with_nan(os.path.join(directory, "output"))
    message = [line for line in log.splitlines() if "error" in line.lower()][:1]
    check(code == 1 and not CRASH.search(run_log) and expect in log and not nan_files,
          f"{name}: exit {code}, {message[0][:160] if message else 'no error line'}"
          + (f", NaN in {nan_files}" if nan_files else "") + ("" if expect in log else f" (expected '{expect}')"))

print(f"corpus: {len(cases)} cases; clean errors {tally['clean error']}, crashes {tally['crash']}, "
      f"hangs {tally['hang']}, accepted {tally['accepted']}")
check.finish()
