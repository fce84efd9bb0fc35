# Hostile and careless input, meshes and messages: volumes Gmsh cannot fill, repeated or stray
# elements and nodes in .msh files, parameters of another mesh type, echoed text that must stay
# short, memory, extreme parameter values, encodings, and the command line's Kokkos option.

# emc_mesh_input FILE MESH: a valid input (good_box.xml's time and material) whose one body,
# "block", has the Mesh parameters MESH (XML <Parameter> lines).
emc_mesh_input() {
  cat >"$1" <<EOF
<ParameterList name="mesh_case">
  <ParameterList name="Time">
    <Parameter name="dt" type="double" value="0.01"/>
    <Parameter name="end" type="double" value="0.02"/>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block">
      <ParameterList name="Mesh">
        $2
      </ParameterList>
      <ParameterList name="Material">
        <Parameter name="young" type="double" value="1e5"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
EOF
}

# emc_msh_input FILE MSH: emc_mesh_input with a Mesh of type file reading MSH.
emc_msh_input() {
  emc_mesh_input "$1" "<Parameter name=\"type\" type=\"string\" value=\"file\"/>
        <Parameter name=\"file\" type=\"string\" value=\"$2\"/>"
}

# expect_no_monitors: the refused run left no monitors.csv in out/.
expect_no_monitors() {
  if [ -e out/monitors.csv ]; then
    echo "the refused run wrote out/monitors.csv"
    return 1
  fi
}

# expect_err_bytes N: the last command's stderr has at most N bytes.
expect_err_bytes() {
  local n
  n=$(wc -c <last.err)
  if [ "$n" -gt "$1" ]; then
    echo "stderr has $n bytes (at most $1 allowed):"
    head -c 600 last.err
    return 1
  fi
}

# --- built-in volumes that Gmsh cannot fill ---

# a wall of 1e-7 under a size of 0.05 meshed to no tetrahedra: a rigid surface without a word
hostile_thin_spherical_shell_refused() {
  emc_mesh_input in.xml '<Parameter name="type" type="string" value="spherical shell"/>
        <Parameter name="inner radius" type="double" value="0.0999999"/>
        <Parameter name="outer radius" type="double" value="0.1"/>
        <Parameter name="size" type="double" value="0.05"/>'
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "in.xml: Bodies/block/Mesh: Gmsh made no tetrahedra of the spherical shell of inner radius 0.0999999, outer radius 0.1 with size 0.05"
  expect_short_err 1
  expect_no_monitors
}

hostile_thin_hollow_cylinder_refused() {
  emc_mesh_input in.xml '<Parameter name="type" type="string" value="hollow cylinder"/>
        <Parameter name="inner radius" type="double" value="0.0999999"/>
        <Parameter name="outer radius" type="double" value="0.1"/>
        <Parameter name="size" type="double" value="0.05"/>'
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "Bodies/block/Mesh: Gmsh made no tetrahedra of the hollow cylinder of height 0.1, inner radius 0.0999999, outer radius 0.1"
  expect_short_err 1
  expect_no_monitors
}

# OpenCASCADE fails on a sliver without a reason: refused before Gmsh, naming the parameter
hostile_box_sliver_names_the_corner() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "--set=Bodies/block/Mesh/upper corner={0.1, 1e-9, 0.1}" --output out
  expect_err "Bodies/block/Mesh: parameter 'upper corner': the side along y \('upper corner' - 'lower corner'\) is 1e-09, below 1e-6 of the body's largest extent 0.1"
  expect_short_err 1
}

# --- .msh files: repeated tets, a second copy, a stray node, a NUL byte ---

# ball.msh with tet 315 given again as element 1013
emc_ball_with_repeated_tet() {
  /usr/bin/python3 - "$HERE/../../inputs/meshes/ball.msh" "$1" <<'EOF'
import sys
L = open(sys.argv[1]).read().split('\n')
i = L.index('3 1 4 698')
L[i] = '3 1 4 699'
L.insert(i + 2, ' '.join(['1013'] + L[i + 1].split()[1:]))
j = L.index('2 1012 1 1012')
L[j] = '2 1013 1 1013'
open(sys.argv[2], 'w').write('\n'.join(L))
EOF
}

hostile_msh_repeated_tet_refused() {
  emc_ball_with_repeated_tet dup.msh
  emc_msh_input in.xml dup.msh
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "in.xml: Bodies/block/Mesh: 'dup.msh': elements 315 and 1013 have the same 4 nodes"
  expect_short_err 1
  expect_no_monitors
}

# the ball's tets twice, the second time on new nodes at the same coordinates
hostile_msh_second_copy_refused() {
  /usr/bin/python3 - "$HERE/../../inputs/meshes/ball.msh" copy.msh <<'EOF'
import sys
L = open(sys.argv[1]).read().split('\n')
def section(name):
    return L.index('$' + name), L.index('$End' + name)
# nodes: one more block holding the volume's nodes again, tags + 1000
a, b = section('Nodes')
head = L[a + 1].split()
nodes = []  # (tag, xyz) of every node
k = a + 2
while k < b:
    dim, ent, par, n = map(int, L[k].split())
    tags = L[k + 1:k + 1 + n]
    xyz = L[k + 1 + n:k + 1 + 2 * n]
    nodes += list(zip(tags, xyz))
    k += 1 + 2 * n
extra = ['3 1 0 %d' % len(nodes)] + [str(int(t) + 1000) for t, _ in nodes] + [x for _, x in nodes]
L[a + 1] = '%d %d 1 %d' % (int(head[0]) + 1, 2 * len(nodes), int(head[3]) + 1000)
L[b:b] = extra
# elements: one more tet block on the copied nodes, tags + 2000
a, b = section('Elements')
head = L[a + 1].split()
i = L.index('3 1 4 698')
tets = L[i + 1:i + 699]
copy = ['3 1 4 698'] + [' '.join([str(int(t.split()[0]) + 2000)] +
                                  [str(int(n) + 1000) for n in t.split()[1:]]) for t in tets]
L[a + 1] = '%d %d 1 %d' % (int(head[0]) + 1, int(head[1]) + 698, int(head[3]) + 2000)
L[b:b] = copy
open(sys.argv[2], 'w').write('\n'.join(L))
EOF
  emc_msh_input in.xml copy.msh
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "in.xml: Bodies/block/Mesh: 'copy.msh': elements [0-9]+ and [0-9]+ lie on the same 4 points through different nodes"
  expect_short_err 1
  expect_no_monitors
}

# one node at x = 1e308 was blamed on a normal element ("element 109 is degenerate")
hostile_msh_far_node_named() {
  sed 's/^-0.05639451083650288 /1e308 /' "$HERE/../../inputs/meshes/ball.msh" >far.msh
  emc_msh_input in.xml far.msh
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "'far.msh': node [0-9]+ has the coordinate x = 1e\+308; coordinates must be finite numbers of magnitude at most 1e30"
  expect_short_err 1
  if grep -q degenerate last.err; then echo "a normal element blamed"; return 1; fi
}

# a NUL byte in a section header cut the message where it was printed
hostile_msh_nul_byte_escaped() {
  /usr/bin/python3 -c "import sys; open('nul.msh','wb').write(open(sys.argv[1],'rb').read().replace(b'\$Nodes', b'\$No\x00des', 1))" \
    "$HERE/../../inputs/meshes/ball.msh"
  emc_msh_input in.xml nul.msh
  expect_exit 1 "$EMC" in.xml --output out
  expect_err 'line 20 \(\$No\\0des\): section \$No\\0des has no \$EndNo\\0des line'
  expect_short_err 1
}

# --- a parameter of another mesh type is refused, not ignored ---

hostile_mesh_file_on_a_box_refused() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml --set Bodies/block/Mesh/file=meshes/ball.msh --output out
  expect_err 'in.xml: parameter "Bodies/block/Mesh/file": given, but type "box" does not read it \(it is a parameter of type "file"\); allowed: the parameters of type "box": type, size, lower corner, upper corner'
  expect_short_err 1
  expect_no_monitors
}

hostile_radius_on_a_box_refused() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "--set=Bodies/block/Mesh/outer radius=0.3" --output out
  expect_err 'parameter "Bodies/block/Mesh/outer radius": given, but type "box" does not read it \(it is a parameter of types "hollow cylinder", "spherical shell"\)'
  expect_short_err 1
}

# --- echoed text stays short ---

hostile_long_output_name_shortened() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml --output "$(printf 'b%.0s' $(seq 1 5000))"
  expect_err '^error: --output "b{80}\.\.\. \(5000 characters\)": a name in it has 5000 bytes; allowed: names of at most 255 bytes'
  expect_err_bytes 300
}

hostile_long_ifpack2_name_shortened() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml --set Output/every=0 --output out \
    "--set=Solver/Linear/Ifpack2/$(printf 'f%.0s' $(seq 1 5000))=1"
  expect_err 'warning: .*Solver/Linear/Ifpack2: "f{80}\.\.\. \(5000 characters\)" not known to Ifpack2'
  expect_err_bytes 1000
}

hostile_many_unknown_belos_names_listed_briefly() {
  emc_good_input in.xml
  local sets=() i
  for i in $(seq 1 300); do sets+=("--set=Solver/Linear/Belos/typo $i=1"); done
  expect_exit 0 "$EMC" in.xml --set Output/every=0 --output out "${sets[@]}"
  expect_err 'warning: .*Solver/Linear/Belos: "typo [0-9]+", .* and 295 more not known to Belos'
  expect_err_bytes 600
}

hostile_long_surface_name_shortened() {
  local s
  s=$(printf 's%.0s' $(seq 1 5000))
  cp "$HERE/../regression/two_blocks.xml" in.xml
  expect_exit 1 "$EMC" in.xml "--set=Contact/A on B/slave=A/$s" --output out
  expect_err "has no surface \"s{80}\.\.\. \(5000 characters\)\""
  expect_err_bytes 400
  sed 's|^</ParameterList>|<ParameterList name="Dirichlet"><ParameterList name="fix"><Parameter name="body" type="string" value="block"/><Parameter name="surface" type="string" value="xmin"/></ParameterList></ParameterList></ParameterList>|' \
    "$HERE/good_box.xml" >fix.xml
  expect_exit 1 "$EMC" fix.xml "--set=Dirichlet/fix/surface=$s" --output out
  expect_err "unknown surface 's{80}\.\.\. \(5000 characters\)'"
  expect_err_bytes 400
}

hostile_long_mesh_file_name_shortened() {
  emc_msh_input in.xml "$(printf 'm%.0s' $(seq 1 250))/$(printf 'n%.0s' $(seq 1 250)).msh"
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "mesh file 'm{80}\.\.\. \(505 characters\)' does not exist"
  expect_err_bytes 300
}

# MueLu printed the edit distance of its 190 valid names to a typo on stdout
hostile_muelu_typo_quiet() {
  # needs MueLu
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml --set Solver/Linear/preconditioner=muelu \
    "--set=Solver/Linear/MueLu/smother: type=RELAXATION" --output out
  expect_err 'parameter "Solver/Linear/MueLu": MueLu refused it: .*smother: type'
  expect_short_err 1
  if [ -s last.out ]; then
    echo "stdout has $(wc -l <last.out) lines:"
    head -5 last.out
    return 1
  fi
}

# a node index of 1e300 in a forged checkpoint was printed with 300 digits (two blocks in
# contact checkpointed at step 6 with active entries, the first entry's node forged)
hostile_checkpoint_huge_node_index_short() {
  cp "$HERE/../regression/two_blocks.xml" in.xml
  "$EMC" in.xml --set Output/progress=false --set Time/end=0.06 --set "Output/checkpoint every=6" \
    --output ck >ck.log 2>&1
  HERE="$HERE" /usr/bin/python3 - ck/checkpoint.h5 <<'EOF'
import os, sys
import h5py, numpy as np
sys.path.insert(0, os.environ['HERE'])
from checkpoint_state import checksum
with h5py.File(sys.argv[1], 'r+') as f:
    active = f['active'][:]
    assert len(active) > 0, 'no active entry'
    active[0] = 1e300
    del f['active']
    f.create_dataset('active', data=active, dtype='<f8')
    f.attrs.modify('checksum', np.uint64(checksum(f, f['state'][:])))
EOF
  expect_exit 1 "$EMC" in.xml --set Time/end=0.08 --restart ck/checkpoint.h5
  expect_err 'node 1e\+300'
  expect_err_bytes 400
}

# --- memory ---

# ulimit -v 1200000 and 740000 tets: a Kokkos traceback and exit 2; now refused before meshing
hostile_out_of_memory_one_line() {
  cp "$HERE/../../inputs/tumbling_box.xml" in.xml
  expect_exit 1 bash -c "ulimit -v 1200000; exec \"$EMC\" in.xml --set Bodies/box/Mesh/size=0.012 --output out"
  expect_err 'in.xml: Bodies: the meshes would hold about 737847 tetrahedra in all \(box: 737847\), which would need about [0-9.]+ GiB per rank .* more than the [0-9.]+ GiB this rank can still get \(the address space limit'
  expect_short_err 1
  expect_no_monitors
}

# the same when an allocation fails anyway (here GMRES's Krylov basis of 400000 vectors)
hostile_failed_allocation_one_line() {
  emc_good_input in.xml
  expect_exit 1 bash -c "ulimit -v 1000000; exec \"$EMC\" in.xml '--set=Solver/Linear/Belos/Num Blocks=100000' '--set=Solver/Linear/max iterations=100000' --output out"
  expect_err '^error: out of memory \(.*Solver/Linear/Belos.*\), with 1134 tets, 344 nodes on 1 rank\(s\)'
  expect_short_err 1
}

# the tet limit is over all bodies: two boxes of about 1.17e8 tets each (each below the limit,
# so each was meshed)
hostile_tet_limit_over_all_bodies() {
  cat >in.xml <<'EOF'
<ParameterList name="two_big">
  <ParameterList name="Time">
    <Parameter name="dt" type="double" value="0.01"/>
    <Parameter name="end" type="double" value="0.02"/>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="a">
      <ParameterList name="Mesh">
        <Parameter name="size" type="double" value="0.0009"/>
        <Parameter name="upper corner" type="Array(double)" value="{0.1, 0.1, 1}"/>
      </ParameterList>
    </ParameterList>
    <ParameterList name="b">
      <ParameterList name="Mesh">
        <Parameter name="size" type="double" value="0.0009"/>
        <Parameter name="lower corner" type="Array(double)" value="{0, 0, 2}"/>
        <Parameter name="upper corner" type="Array(double)" value="{0.1, 0.1, 3}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
EOF
  expect_exit_within 60 1 "$EMC" in.xml --output out
  expect_err 'in.xml: Bodies: the meshes would hold about 233196159 tetrahedra in all \(a: 116598080, b: 116598080\), more than the limit of 200000000 tetrahedra in all the bodies together'
  expect_short_err 1
}

# --- extreme values: refused naming the parameter, or named when the step fails ---

hostile_extreme_material_refused() {
  emc_good_input in.xml
  local v
  for v in "Material/density=1e308" "Material/young=1e308" "Material/young=4.9e-324" \
    "Material/poisson=0.4999999999" "Initial/velocity={1e20, 0, 0}"; do
    expect_exit 1 "$EMC" in.xml "--set=Bodies/block/$v" --output out
    expect_err "override \"Bodies/block/${v%%=*}=.*out of range; allowed: "
    expect_short_err 1
  done
  expect_exit 1 "$EMC" in.xml "--set=Loads/gravity={0, 0, -1e300}" --output out
  expect_err 'override "Loads/gravity=.*has a component out of range; allowed: exactly 3 numbers \{x, y, z\} each >= -1e12 and <= 1e12'
}

hostile_extreme_solver_values_refused() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "--set=Solver/Linear/Belos/Maximum Iterations=-1" --output out
  expect_err 'parameter "Solver/Linear/Belos/Maximum Iterations": value -1 is out of range; allowed: an int >= 1'
  expect_exit 1 "$EMC" in.xml --set Solver/Linear/tolerance=1e300 --output out
  expect_err 'override "Solver/Linear/tolerance=1e300": value 1e300 is out of range; allowed: a double > 0 and < 1'
  expect_short_err 1
}

# a mesh squashed to 1e-9 of its height: every step failed; now its flat elements are refused
hostile_squashed_msh_refused() {
  /usr/bin/python3 - "$HERE/../../inputs/meshes/ball.msh" flat.msh <<'EOF'
import sys
L = open(sys.argv[1]).read().split('\n')
a, b = L.index('$Nodes'), L.index('$EndNodes')
k = a + 2
while k < b:
    n = int(L[k].split()[3])
    for i in range(k + 1 + n, k + 1 + 2 * n):
        x, y, z = map(float, L[i].split())
        L[i] = '%r %r %r' % (x, y, z * 1e-9)
    k += 1 + 2 * n
open(sys.argv[2], 'w').write('\n'.join(L))
EOF
  emc_msh_input in.xml flat.msh
  expect_exit 1 "$EMC" in.xml --output out
  expect_err "'flat.msh': element [0-9]+ is flat \(its volume is [0-9.e-]+ of a regular tetrahedron's on its longest edge"
  expect_short_err 1
}

# accepted values whose first step cannot be solved: the message names the parameters
hostile_unsolvable_step_names_parameters() {
  emc_good_input in.xml
  expect_exit 1 "$EMC" in.xml "--set=Bodies/block/Initial/angular velocity={1e6, 0, 0}" \
    --set Output/every=0 --output out
  expect_err 'step 1 at t = 0 could not be solved.*; parameters that may keep the step from being solved: Bodies/block/Initial/angular velocity = \{1e6, 0, 0\} turns the body by [0-9.e+]+ rad even in the smallest step'
  expect_short_err 1
  cp "$HERE/../../inputs/tumbling_box.xml" box.xml
  # a step so long that the inertia drowns in the stiffness' round-off: refused before the first
  # step, naming the density and the step
  expect_exit 1 "$EMC" box.xml --set Time/dt=1e21 --set Time/end=1e22 --set Output/every=0 \
    --output out2
  expect_err 'parameter "Bodies/box/Material/density": .* below the round-off of its stiffness .* at Time/dt = 1e\+21'
  expect_short_err 1
}

# values of real materials stay accepted: steel, rubber
hostile_real_materials_accepted() {
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml --set Bodies/block/Material/young=2.1e11 \
    --set Bodies/block/Material/density=7850 --set Output/every=0 --output steel
  expect_exit 0 "$EMC" in.xml --set Bodies/block/Material/young=1e6 \
    --set Bodies/block/Material/poisson=0.49 --set Output/every=0 --output rubber
}

# --- encodings ---

hostile_utf8_bom_input_accepted() {
  printf '\xef\xbb\xbf' >in.xml
  cat "$HERE/good_box.xml" >>in.xml
  expect_exit 0 "$EMC" in.xml --set Output/every=0 --output out
}

hostile_utf16_input_refused() {
  iconv -f UTF-8 -t UTF-16 "$HERE/good_box.xml" >in.xml
  expect_exit 1 "$EMC" in.xml --output out
  expect_err 'in.xml: cannot read the input: it is UTF-16 text \(a byte order mark\); it must be UTF-8 \(or ASCII\) text'
  expect_short_err 1
  iconv -f UTF-8 -t UTF-16LE "$HERE/good_box.xml" >le.xml  # no byte order mark
  expect_exit 1 "$EMC" le.xml --output out
  expect_err 'le.xml: cannot read the input: it holds a NUL byte \(byte 1\): not text, or UTF-16; it must be UTF-8'
}

# --- the command line ---

# --help's Kokkos example must be an option the linked Kokkos accepts
hostile_help_kokkos_example_accepted() {
  local option
  option=$("$EMC" --help | grep -o -- '--kokkos-[a-z-]*=N' | head -1)
  [ -n "$option" ] || { echo "no Kokkos option in --help"; return 1; }
  emc_good_input in.xml
  expect_exit 0 "$EMC" in.xml "${option%=N}=1" --set Output/every=0 --output out
}
