#!/bin/bash
# Build with AddressSanitizer + UndefinedBehaviorSanitizer outside the source
# tree and run the ctest suite (or a subset) under them; then summarise the
# sanitizer reports, per test.
#
#   contrib/sanitize.sh [BUILD_DIR] [ctest selection, e.g. -R 'hertz|stick']
#
# BUILD_DIR defaults to ${SL_SANITIZE_BUILD:-/tmp/sl-sanitize-build} and must
# lie outside the source tree. Environment: SL_SANITIZE_JOBS (make -j, 1),
# SL_SANITIZE_TIMEOUT (ctest timeout per test in s, 7200), SL_SANITIZE_LEAKS=1
# (turn LeakSanitizer on, with the third-party suppressions below),
# SL_SANITIZE_CXXFLAGS (replaces the sanitizer compile flags), SL_SANITIZE_LOCK
# (a file: cmake and the build run under `flock` on it, e.g. /tmp/sl_build.lock
# where other builds share the machine; the tests do not hold it),
# SL_SANITIZE_TARGETS (the targets built, all by default; the Python tests need
# only stabilized_lagrangian),
# SL_SANITIZE_SOURCE: what is built and tested --
#   copy (default)  a copy of the working tree, taken at the start into
#                   BUILD_DIR/source, so edits made while it builds and runs
#                   (a header changed half-way) cannot mix two versions;
#   tree            the working tree itself;
#   <git revision>  e.g. HEAD: that commit, by `git archive`, into BUILD_DIR/source.
# Report paths are given relative to the source tree (source/..., include/...).
# Exit status: 0 when every selected test passed and no sanitizer report was
# found (in the log files or in a test's output; a test that expects the
# program to fail can pass while the program died of a report), 1 otherwise
# (contrib/build_and_test.sh relies on it), 2 for a wrong build folder or
# selection.
#
# Choices:
# - Release deal.II (libdeal.ii.so, CMAKE_BUILD_TYPE=Release). The Debian
#   package also has libdeal.ii.g.so, but its Debug flavour compiles our code
#   at -O0 with deal.II's Asserts on and is several times slower again; the
#   sanitizers are the point here. deal.II, Trilinos, MPI, ... are not
#   instrumented: only our code (and the deal.II/Trilinos header templates
#   compiled into it) is checked.
# - deal_ii_setup_target() adds deal.II's own flags (-O2 -g -funroll-loops ...)
#   as target options, i.e. after CMAKE_CXX_FLAGS, so a -O1 there would lose.
#   A compiler launcher generated in BUILD_DIR appends -O1 -g1 last instead
#   (the sanitizer flags themselves go through CMAKE_CXX_FLAGS and the linker
#   flags; `make VERBOSE=1` shows the result). -g1 keeps the line tables and
#   inlined frames a report's stack shows, without the full debug information
#   of every deal.II template: a quarter less compile time, half the objects.
# - detect_leaks=0: Open MPI (and its PMIx/hwloc/UCX components), Trilinos'
#   static registries and deal.II's MPI/p4est set-up leave memory allocated at
#   exit on purpose, which would fail every run. SL_SANITIZE_LEAKS=1 turns LSan
#   on with a suppressions file for those third-party libraries only.
# - BUILD_DIR/sanitize/shim.c, linked into this build's executables only:
#   (1) ASan reserves terabytes of address space at start-up (shadow memory),
#   so the meshing child's RLIMIT_AS (gmsh_mesh.cc) would make each of its
#   mmaps fail ("ERROR: Failed to mmap": every .geo scene fails); its
#   setrlimit() counts RLIMIT_AS on top of what is already mapped. (2) GCC's
#   libasan and libubsan each have their own report file, and with both
#   linked UBSan ignores UBSAN_OPTIONS=log_path (it writes to stderr); a
#   constructor hands that path to libubsan. (3) A process that limits its own
#   address space (the meshing child) writes its reports to
#   LOG_PATH.limited.PID: the meshing memory limit reached there ends the
#   child with ASan's "allocator is out of memory" where the normal build
#   throws std::bad_alloc (tests/bad_input_corpus.py, huge.geo), which is the
#   limit at work, not a bug; the summary lists such out-of-memory reports
#   apart and does not count them (any other report in those files counts).
# - halt_on_error=1, abort_on_error=0: the first report ends the process with
#   exit code 1 (not a core dump); log_path collects the reports in files,
#   since most Python tests only look at exit codes and print the program's
#   output only on failure.
set -euo pipefail
cd "$(dirname "$0")/.."
tree_dir=$(pwd -P)

build_dir=${SL_SANITIZE_BUILD:-/tmp/sl-sanitize-build}
if [[ $# -gt 0 && $1 != -* ]]; then
  build_dir=$1
  shift
fi
build_dir=$(realpath -m "$build_dir")
case "$build_dir/" in
  "$tree_dir"/*) echo "sanitize.sh: $build_dir is inside the source tree; choose another" >&2
                   exit 2 ;;
esac
mkdir -p "$build_dir"
source_mode=${SL_SANITIZE_SOURCE:-copy}
if [[ $source_mode == tree ]]; then
  source_dir=$tree_dir
else
  source_dir=$build_dir/source
  staging=$build_dir/source.new
  rm -rf "$staging"
  mkdir -p "$staging" "$source_dir"
  if [[ $source_mode == copy ]]; then
    tar -C "$tree_dir" --exclude='./build*' --exclude=./.git --exclude='./output*' \
        --exclude='__pycache__' -cf - . | tar -C "$staging" -xf -
  else
    git -C "$tree_dir" archive "$source_mode" | tar -C "$staging" -xf -
  fi
  # only changed files are replaced, with a fresh mtime: make rebuilds what changed (also
  # when going back to an older revision) and no more
  (cd "$staging" && find . -type f) | while read -r f; do
    if ! cmp -s "$staging/$f" "$source_dir/$f"; then
      mkdir -p "$(dirname "$source_dir/$f")"
      cp "$staging/$f" "$source_dir/$f"
    fi
  done
  (cd "$source_dir" && find . -type f) | while read -r f; do
    [[ -e $staging/$f ]] || rm -f "$source_dir/$f"
  done
  rm -rf "$staging"
fi
echo "sanitize.sh: building $source_mode ($source_dir) in $build_dir"
jobs=${SL_SANITIZE_JOBS:-1}
test_timeout=${SL_SANITIZE_TIMEOUT:-7200}
sanitize_flags=${SL_SANITIZE_CXXFLAGS:-"-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"}
link_flags="-fsanitize=address,undefined"

# --- build -----------------------------------------------------------------
support=$build_dir/sanitize
mkdir -p "$support"
cat > "$support/cxx-launcher.sh" <<'EOF'
#!/bin/sh
# CMAKE_CXX_COMPILER_LAUNCHER: deal.II's target flags contain -O2 -g; the last -O and -g win.
exec "$@" -O1 -g1
EOF
chmod +x "$support/cxx-launcher.sh"

cat > "$support/shim.c.new" <<'EOF'
/* Linked into the sanitizer build's executables (see sanitize.sh). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

static rlim_t mapped_bytes(void)
{
  char buffer[4096];
  const int fd = open("/proc/self/status", O_RDONLY);
  if (fd < 0)
    return 0;
  const ssize_t n = read(fd, buffer, sizeof buffer - 1);
  close(fd);
  if (n <= 0)
    return 0;
  buffer[n] = 0;
  const char *size = strstr(buffer, "VmSize:");
  return size ? (rlim_t)strtoull(size + 7, NULL, 10) * 1024 : 0;
}

/* libasan's (the executable binds to it) */
void __sanitizer_set_report_path(const char *path);
/* libubsan's own copy, found by the constructor */
static void (*ubsan_set_report_path)(const char *);

/* The log_path of the options in the environment variable `variable`, followed by `suffix`,
   into path; 0 when there is none. */
static int log_path(const char *variable, const char *suffix, char *path, size_t size)
{
  const char *options = getenv(variable);
  const char *start   = options ? strstr(options, "log_path=") : NULL;
  if (!start)
    return 0;
  start += strlen("log_path=");
  const size_t n = strcspn(start, ":");
  if (n + strlen(suffix) >= size)
    return 0;
  memcpy(path, start, n);
  strcpy(path + n, suffix);
  return 1;
}

/* RLIMIT_AS is counted on top of the address space already mapped (ASan's shadow); the
   process's reports go to LOG_PATH.limited.PID from then on. */
int setrlimit(__rlimit_resource_t resource, const struct rlimit *limit)
{
  struct rlimit adjusted = *limit;
  if (resource == RLIMIT_AS)
    {
      const rlim_t mapped = mapped_bytes();
      if (adjusted.rlim_cur != RLIM_INFINITY)
        adjusted.rlim_cur += mapped;
      if (adjusted.rlim_max != RLIM_INFINITY)
        adjusted.rlim_max += mapped;
      char path[4096];
      if (log_path("ASAN_OPTIONS", ".limited", path, sizeof path))
        __sanitizer_set_report_path(path);
      if (ubsan_set_report_path && log_path("UBSAN_OPTIONS", ".limited", path, sizeof path))
        ubsan_set_report_path(path);
    }
  return syscall(SYS_prlimit64, 0, resource, &adjusted, NULL) == 0 ? 0 : -1;
}

/* UBSAN_OPTIONS=log_path, which libubsan ignores when libasan is loaded too. */
__attribute__((constructor)) static void ubsan_log_path(void)
{
  void *ubsan = dlopen("libubsan.so.1", RTLD_NOW | RTLD_NOLOAD);
  if (!ubsan)
    return;
  ubsan_set_report_path = (void (*)(const char *))dlsym(ubsan, "__sanitizer_set_report_path");
  char path[4096];
  if (ubsan_set_report_path && log_path("UBSAN_OPTIONS", "", path, sizeof path))
    ubsan_set_report_path(path);
}
EOF
if [[ ! -f $support/shim.o ]] || ! cmp -s "$support/shim.c.new" "$support/shim.c"; then
  mv "$support/shim.c.new" "$support/shim.c"
  cc -O1 -g -fPIC -Wall -c "$support/shim.c" -o "$support/shim.o"
  # the executables link shim.o, which their build rules do not know of: link them again
  rm -f "$build_dir/stabilized_lagrangian"
  if [[ -d $build_dir/tests ]]; then
    find "$build_dir/tests" -maxdepth 1 -type f -name 'test_*' -delete
  fi
fi
rm -f "$support/shim.c.new"

build_start=$SECONDS
# a cache made from another source directory (another SL_SANITIZE_SOURCE) is refused by cmake
if [[ -f $build_dir/CMakeCache.txt ]] &&
   ! grep -qx "CMAKE_HOME_DIRECTORY:INTERNAL=$source_dir" "$build_dir/CMakeCache.txt"; then
  rm -rf "$build_dir/CMakeCache.txt" "$build_dir/CMakeFiles"
fi
locked=()
[[ -n ${SL_SANITIZE_LOCK:-} ]] && locked=(flock "$SL_SANITIZE_LOCK")
"${locked[@]}" cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS="$sanitize_flags" \
      -DCMAKE_EXE_LINKER_FLAGS="$link_flags $support/shim.o" -DCMAKE_SHARED_LINKER_FLAGS="$link_flags" \
      -DCMAKE_CXX_COMPILER_LAUNCHER="$support/cxx-launcher.sh"
targets=()
for target in ${SL_SANITIZE_TARGETS:-}; do
  targets+=(--target "$target")
done
"${locked[@]}" cmake --build "$build_dir" -j"$jobs" "${targets[@]}"
build_time=$((SECONDS - build_start))

# --- suppressions (third-party libraries only) ------------------------------
cat > "$support/lsan.supp" <<'EOF'
# used only with SL_SANITIZE_LEAKS=1: allocations these libraries keep until exit
leak:libmpi.so
leak:libopen-pal.so
leak:libopen-rte.so
leak:libpmix.so
leak:libhwloc.so
leak:libucs.so
leak:libucp.so
leak:libtrilinos_
leak:libdeal.ii
leak:libmumps
leak:libp4est
leak:libsc-
leak:libgmsh.so
leak:libtbb
EOF
cat > "$support/ubsan.supp" <<'EOF'
# UBSan checks run only in instrumented code (ours, and header templates compiled
# into it); nothing suppressed so far.
EOF

# --- tests -----------------------------------------------------------------
logs=$build_dir/sanitizer-logs
rm -rf "$logs"
mkdir -p "$logs"
cd "$build_dir"
mapfile -t tests < <(ctest -N "$@" | sed -n 's/^ *Test *#[0-9]*: *//p')
if [[ ${#tests[@]} -eq 0 ]]; then
  echo "sanitize.sh: no test selected by: $*" >&2
  exit 2
fi
leaks=0
[[ ${SL_SANITIZE_LEAKS:-0} == 1 ]] && leaks=1

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export LSAN_OPTIONS="suppressions=$support/lsan.supp:print_suppressions=1"
results=()
tests_start=$SECONDS
for t in "${tests[@]}"; do
  mkdir -p "$logs/$t"
  start=$SECONDS
  status=passed
  if ! ASAN_OPTIONS="detect_leaks=$leaks:halt_on_error=1:abort_on_error=0:check_initialization_order=1:log_path=$logs/$t/asan" \
       UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$support/ubsan.supp:log_path=$logs/$t/ubsan" \
       ctest -R "^${t}\$" --output-on-failure --timeout "$test_timeout" > "$logs/$t/ctest.log" 2>&1; then
    status=FAILED
    if grep -q "\*\*\*Timeout" "$logs/$t/ctest.log"; then
      status=TIMEOUT          # ctest's limit
    elif grep -q "TimeoutExpired\|still running after" "$logs/$t/ctest.log"; then
      status=TIMEOUT-RUN      # a run's own limit inside the Python test
    fi
  fi
  results+=("$t $status $((SECONDS - start))")
  printf '%-26s %-11s %5d s\n' "$t" "$status" $((SECONDS - start))
done
tests_time=$((SECONDS - tests_start))

# --- summary ---------------------------------------------------------------
echo
echo "=== sanitizer summary (build $build_dir) ==="
echo "build: ${build_time} s, tests: ${tests_time} s, ctest timeout ${test_timeout} s per test"
echo "LeakSanitizer: $([[ $leaks == 1 ]] && echo "on, suppressed: $(grep -v '^#' "$support/lsan.supp" | tr '\n' ' ')" || echo off)"
echo "UBSan suppressions: $(grep -vc '^#' "$support/ubsan.supp" || true) entries"
printf '%s\n' "${results[@]}" > "$logs/results.txt"
cat > "$support/summarize.py" <<'EOF'
"""Per test: status and number of sanitizer reports (in the log_path files and in the
test's own output); then each distinct report (kind, our top frame) with its first frames."""
import collections, glob, os, re, sys
logs, source, results = sys.argv[1:4]
# reports, and the sanitizer runtime's own failures
report = re.compile(r"ERROR: AddressSanitizer|runtime error:|ERROR: LeakSanitizer|"
                    r"ERROR: Failed to mmap|Sanitizer CHECK failed|AddressSanitizer failed")
frame = re.compile(r"^\s*#(\d+) 0x[0-9a-f]+ (?:in (.*) )?(\S+)$")
# memory exhausted: in a process under its own address-space limit (LOG_PATH.limited.PID, the
# meshing child) the limit at work, not counted
out_of_memory = re.compile(r"allocator is out of memory|failed to allocate|Failed to mmap")
ours = re.compile(re.escape(source) + r"/(source|include|tests)/")


def blocks(text):
    """(first line, frames of its first stack) for each report in text"""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if report.search(line):
            frames = []
            for l in lines[i + 1:i + 200]:
                if frame.match(l):
                    frames.append(l.strip())
                elif frames or report.search(l):
                    break
            yield line.strip(), frames


distinct = collections.OrderedDict()
limited = []
for line in open(results):
    name, status, seconds = line.split()
    found, n_limited = [], 0
    for f in sorted(glob.glob(os.path.join(logs, name, "*san.*"))):
        for b in blocks(open(f, errors="replace").read()):
            if ".limited." in os.path.basename(f) and out_of_memory.search(b[0]):
                n_limited += 1
                limited.append((b[0], name, f))
            else:
                found.append((b, f))
    n_files = len(found)
    log = os.path.join(logs, name, "ctest.log")
    found += [(b, log) for b in blocks(open(log, errors="replace").read())]
    print(f"{name:26s} {status:11s} {seconds:>5s} s  sanitizer reports: {n_files} in log files"
          + (f", {len(found) - n_files} in the test output" if len(found) > n_files else "")
          + (f" (and {n_limited} out of memory under the process's own limit)" if n_limited else ""))
    for (head, frames), where in found:
        top = next((frame.match(l).group(3) for l in frames if ours.search(l)),
                   "(no frame in our code)")
        kind = re.sub(r"0x[0-9a-f]+|==\d+==|\(pid=\d+\)|^.*?(?=runtime error:)", "", head)
        kind = re.sub(r"\s+", " ", kind).strip()
        key = (kind, top.replace(source + "/", ""))
        if key not in distinct:
            distinct[key] = (head, frames, where, set())
        distinct[key][3].add(name)
if limited:
    print(f"\nnot counted: {len(limited)} out-of-memory report line(s) of processes under their own"
          " address-space limit (the meshing child's Geometry/gmsh/Meshing memory limit reached):")
    for head, name, where in limited:
        print(f"    {name}: {head.strip()[:120]}  ({where})")
print(f"\n{len(distinct)} distinct sanitizer report(s)")
open(os.path.join(logs, "n_reports"), "w").write(f"{len(distinct)}\n")
for (kind, top), (head, frames, where, names) in distinct.items():
    print(f"--- {head.replace(source + '/', '')}\n    our top frame: {top}"
          f"\n    tests: {' '.join(sorted(names))}\n    e.g. in {where}")
    if re.search(r"failed to allocate|Failed to mmap|ReserveShadowMemoryRange", head):
        print("    (the sanitizer runtime could not map memory: an address-space limit, RLIMIT_AS or"
              " ulimit -v, on the process; ASan needs terabytes of it, so not a bug of ours)")
    for l in frames[:15]:
        print("   ", l.replace(source + "/", ""))
EOF
python3 "$support/summarize.py" "$logs" "$source_dir" "$logs/results.txt"
failed=$(printf '%s\n' "${results[@]}" | awk '$2 != "passed"' | wc -l)
# the output of the tests not passed (CI shows only what is printed)
for t in $(printf '%s\n' "${results[@]}" | awk '$2 != "passed" {print $1}'); do
  echo
  echo "--- $t: the last 60 lines of $logs/$t/ctest.log"
  tail -n 60 "$logs/$t/ctest.log"
done
reports=$(cat "$logs/n_reports")
echo "$failed of ${#tests[@]} test(s) not passed, $reports distinct sanitizer report(s); logs in $logs"
[[ $failed -eq 0 && $reports -eq 0 ]]
