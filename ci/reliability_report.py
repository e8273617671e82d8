#!/usr/bin/env python3
"""Writes docs/RELIABILITY.md from the last runs of ci/fuzz.sh, ci/sanitize.sh and the fault
tests (ci/reliability-report.sh runs them, then this). Every number in the document comes from
those runs' outputs; what is missing is said to be missing, never filled in.

    reliability_report.py OUT.md
"""
import datetime
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FUZZ = os.path.join(ROOT, "build-fuzz")
ASAN = os.path.join(ROOT, "build-asan")
BUILD = os.path.join(ROOT, "build")
FAULTS = os.path.join(BUILD, "test-out", "reliability")

# What each fuzz target reads, through which entry point, with which seeds.
TARGETS = [
    ("vtu", "`io::readMeshFromMemory(bytes, \"fuzz.vtu\")`, then preparation",
     "the file", "tests/io/data/*.vtu (every encoding), ../shared/data/*.vtu"),
    ("pvtu", "`io::readPvtu` with an in-memory `OpenFile`, then preparation",
     "index and pieces separated by `\\n===piece===\\n`; the k-th piece path asked for is part k",
     "tests/io/data/weld.pvtu with its 3 pieces, and with 1"),
    ("legacy_vtk", "`io::readMeshFromMemory(bytes, \"fuzz.vtk\")`, then preparation",
     "the file", "tests/io/data/*.vtk (4.2 and 5.1, ascii and binary), ../shared/data/*.vtk"),
    ("ugrid", "`io::readMeshFromMemory(bytes, \"fuzz.<variant>.ugrid\")`, then preparation",
     "first byte picks the variant (ascii, b8, lb8, b8l, lb8l, b4, lb4, r8, lr8, r4, lr4)",
     "one grid with every element type in all 11 variants (tests/fuzz/make_seeds.py)"),
    ("cache", "`prep::parseCache(data, size, key)`",
     "the file as is, then again with its size and checksum repaired so that mutations reach "
     "the sections", "caches of mesh_ascii.vtu and weld.pvtu, compact and plain, written by "
     "`prep::writeCache` (fuzz_make_cache_seed)"),
    ("colormap", "`scene::parseParaViewColormap(text, \"fuzz.json\")`",
     "the JSON text", "4 ParaView colour maps (RGB, Lab, HSV, Diverging; with and without "
     "opacity points)"),
]

# The fault tests: what is injected and what the test checks.
FAULT_CASES = [
    ("kill_rank", "mpi", "3 ranks, `render --time all`; rank 1 raises SIGKILL at the start of "
     "frame 1 (`SHELLMARCH_FAULT=at=frame,frame=1,rank=1,action=kill`) while ranks 0 and 2 wait "
     "for it in that frame's compositing",
     "mpiexec exits non-zero and says a rank was killed; no hang; frame 0 is a complete PNG; no "
     "file for frames 1 and 2"),
    ("throw_rank", "mpi", "3 ranks; rank 2 throws an ordinary error at the start of frame 1",
     "every rank ends, the output holds `rank 2 of 3 failed: injected fault ...`; PNGs as above"),
    ("corrupt_piece", "mpi", "3 ranks; piece 2 of the .pvtu cut to 3/4 of its size (its header, "
     "which every rank reads to share pieces out, intact), so only its reader fails",
     "every rank ends with a message naming cap_2.vtu; no image"),
    ("same_error", "mpi", "3 ranks; every rank fails the same way: a field no piece has, then "
     "`--fovy 0` (found before MPI starts)",
     "one line reports each (rank 0's; the other ranks wait two seconds before reporting, and "
     "rank 0's abort ends them; the test allows fewer lines than ranks, since a loaded machine "
     "may be slower to end them); no image"),
    ("png_kill", "gpu", "SIGKILL halfway through writing the PNG "
     "(`at=write,match=.png,action=kill`), over an existing a.png",
     "a.png keeps its old content; the partial bytes are only under a temporary name; a new run "
     "writes a complete PNG"),
    ("cache_write", "gpu", "an error halfway through writing the preparation cache",
     "exit status 1 with the message; the cache folder holds neither a cache nor a temporary; "
     "no image"),
    ("cache_corrupt", "gpu", "a cache with 4 bytes overwritten, then one cut short",
     "each is reported (`checksum mismatch`, `payload size does not match`) and replaced; the "
     "replacement is used (`from cache`) and gives the same image"),
    ("oom_scene", "gpu", "`SHELLMARCH_DEVICE_MEMORY_LIMIT=64K`: the scene does not fit",
     "exit status 1, message with the bytes needed and a rank count; no image; the stated need "
     "(+2 MiB for a small image's compositor, +4 MiB for the pre-integrated transfer function) is then enough"),
    ("oom_lists_fixed", "gpu", "fixed lists, K = 16, 512x512, in 28 MiB (4 MiB of it the pre-integrated transfer function)",
     "the message suggests a --k and a --size; both then fit"),
    ("oom_lists_two_pass", "gpu", "two-pass lists, 512x512, in 14 MiB",
     "the message suggests a --size (and ranks); the size then fits"),
    ("overflow", "gpu", "fixed lists with K = 1 where rays cross the capsule's hollow twice",
     "--stats and --stats-json count the overflow, a warning says the image is approximate; "
     "two-pass lists report 0 and do not warn"),
]


def read(path):
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return None


def times(path):
    """'NAME wall user sys' lines -> {name: (wall, cpu)}."""
    out = {}
    for line in (read(path) or "").splitlines():
        parts = line.split()
        if len(parts) == 4:
            try:
                out[parts[0]] = (float(parts[1]), float(parts[2]) + float(parts[3]))
            except ValueError:
                pass
    return out


def junit(path):
    """JUnit from ctest -> [(name, passed, seconds, output, skipped)], or None. Skipped: the test
    skipped itself (GTEST_SKIP; ctest's status "notrun"), neither passed nor failed."""
    if not os.path.exists(path):
        return None
    cases = []
    for c in ET.parse(path).getroot().iter("testcase"):
        out = c.find("system-out")
        cases.append((c.get("name"), c.get("status") == "run", float(c.get("time", 0)),
                      out.text if out is not None and out.text else "",
                      c.get("status") == "notrun"))
    return cases


def mtime(path):
    if not os.path.exists(path):
        return "never"
    return datetime.datetime.fromtimestamp(os.path.getmtime(path)).strftime("%Y-%m-%d %H:%M")


def minutes(s):
    return "%d min %02d s" % (s // 60, s % 60) if s >= 60 else "%.0f s" % s


def first_line(text, pattern):
    for line in (text or "").splitlines():
        if re.search(pattern, line):
            return line.strip()
    return None


def fuzz_section(md):
    md.append("## 1. Fuzzing\n")
    md.append("libFuzzer targets (tests/fuzz/), built by `ci/fuzz.sh` with clang and Debian's "
              "runtime (libclang-rt-14-dev) in build-fuzz/: `-fsanitize=fuzzer,address,undefined`"
              " on the targets and `-fsanitize=fuzzer-no-link,address,undefined` on every library"
              " they reach (so the fuzzer sees coverage inside the readers), `-O1`, "
              "`-D_GLIBCXX_ASSERTIONS` (out-of-range `operator[]` on vectors and arrays is a "
              "finding even within capacity), `-fno-sanitize-recover=all`. Each input goes "
              "through the loader's ordinary entry point; a mesh a reader accepts goes on through"
              " `prep::prepareRank` (connectivity, shell, compaction) when it has at most 4096 "
              "cells. The harness (tests/fuzz/fuzz_inputs.cpp) also treats as a finding: an "
              "exception other than the loader's documented `sm::FileError`, a message that does"
              " not start with the input's name or holds a control character, a mesh that breaks"
              " its invariants (cell ids beyond the points, field lengths, non-finite points), a "
              "cache accepted with inconsistent arrays, a colour table outside [0, 1].\n")
    md.append("Run limits: `-max_len=65536` (larger seeds are read truncated), "
              "`-malloc_limit_mb=256` (no 64 KiB input may make one allocation of 256 MiB: a "
              "64 KiB zlib stream inflates to at most 64 MiB and LZ4 blocks to 16 MiB, and an LZMA "
              "block's size must first match its .xz index, which a CRC32 guards, so more means a "
              "declared size was believed), `-rss_limit_mb=2048`, `-timeout=30` per input (a hang), leak checking "
              "on. Any finding fails CI and names the input to commit.\n")
    md.append("| target | entry point | input layout | seeds |")
    md.append("|---|---|---|---|")
    for t, entry, layout, seeds in TARGETS:
        md.append("| `fuzz_%s` | %s | %s | %s |" % (t, entry, layout, seeds))
    md.append("")
    summary = read(os.path.join(FUZZ, "fuzz-summary.tsv"))
    ft = times(os.path.join(FUZZ, "fuzz-times.txt"))
    md.append("### Last run (%s)\n" % mtime(os.path.join(FUZZ, "fuzz-summary.tsv")))
    if not summary:
        md.append("No results: run `ci/fuzz.sh`.\n")
        return None
    rows = [l.split("\t") for l in summary.strip().splitlines()[1:]]
    md.append("| target | seconds | executions | executions/s | corpus after | coverage (edges) "
              "| result |")
    md.append("|---|---:|---:|---:|---:|---:|---|")
    total = 0
    for r in rows:
        total += int(r[2] or 0)
        md.append("| `fuzz_%s` | %s | %s | %s | %s | %s | %s |" % tuple(r))
    md.append("")
    build = ft.get("build")
    fuzz_wall = sum(w for k, (w, c) in ft.items() if k.startswith("fuzz_"))
    md.append("%d executions in all. Build of the fuzzers: %s; fuzzing: %s.\n" % (
        total, "%s wall, %s CPU" % (minutes(build[0]), minutes(build[1])) if build else "not "
        "timed", minutes(fuzz_wall)))
    failed = [r[0] for r in rows if r[-1] != "ok"]
    return total, failed


# Limits of 32-bit device indices and counters, and the tests that hold each (text, not a run's
# numbers: every figure in it is a limit or an example computed from one).
INDEX_LIMITS = (
    "Shaders index buffers with 32-bit integers, which SPIR-V access chains may read as signed, "
    "so no index may reach 2^31. Sizes that would are refused with one line before the device is "
    "asked for anything: per rank, element records and neighbours of each type, 16-byte vertex "
    "records and the shell's three indices per triangle (`prep::checkShaderIndexRange`, naming "
    "the file, e.g. about 537 million plain tetrahedra or 716 million shell triangles; test "
    "`ShaderIndexRange.*`); the fragments of one rank's two-pass lists "
    "(`PrefixSum::downloadTotal`, summed in 64 bits at the top level, and a block total below it "
    "that would pass 32 bits saturates instead of wrapping; test "
    "`PrefixSum.TotalsBeyond32BitsAreRefused`) and the slots of fixed-length lists, naming `--k` "
    "(`DeepCompositorLimits.*`). A shell with more triangles than the device's acceleration "
    "structures hold (`maxPrimitiveCount`, at least 2^29 - 1; larger builds are undefined "
    "behaviour, not an error the device reports) is refused naming the rank's count and the "
    "limit (`HardCases.ShellBeyondTheDevicesPrimitiveLimitIsRefused`, with the test hook "
    "`SHELLMARCH_AS_PRIMITIVE_LIMIT`). Passes over more than 65 535 workgroups lay them out in "
    "rows (docs/COMPOSITOR.md, \"Limits of one frame\"). The frame's sample and element-step "
    "counters are 64-bit (a carry word): a 4096² demo frame at step 0.015 counts 5 093 897 839 "
    "samples. A sample step finer than the farthest data corner's distance from the eye over "
    "2^24 is refused naming `--step` (in situ `render: sampleDistance`): float distances along a "
    "ray no longer tell such samples apart, and the step index would wrap "
    "(`HardCases.StepFinerThanFloatResolvesIsRefused`, `app.cli-errors`); the viewer's "
    "finer-step key stops at a hundredth of the starting step. Inside the tracer, the "
    "first-sample search stops at index 2^24 too, so an element whose exit distance comes out "
    "infinite or absurd (a degenerate crossing) ends its sampling there instead of counting "
    "forever.\n")


# Limits of counts and buffer sizes at scale, and the tests that hold each (text, not a run's
# numbers).
SCALE_LIMITS = (
    "A mesh holds 32-bit vertex ids, so one mesh (a file, or what one rank reads of a .pvtu) "
    "holds at most 2^32 - 1 points: a .vtu, legacy .vtk or .ugrid header declaring more, or the"
    " pieces one rank is about to read declaring more together (their headers, read first), is "
    "refused before any data is read, naming the file and saying to split it into pieces and "
    "use more ranks (`mesh::checkPointCount`; tests "
    "`MeshBuilder.PointCountsPast32BitIdsAreRefusedAtTheBoundary`, "
    "`Robustness.PointCountsPast32BitIdsAreRefusedBeforeReading`, "
    "`PvtuReader.PiecesPast32BitIdsTogetherAreRefusedBeforeReading`). Cell counts are 64-bit: "
    "past 2^31 and 2^32 they are read where memory allows "
    "(`Robustness.CellCountsPast2To31And2To32AreCheckedAgainstTheData`); only cell origins "
    "(kept for cell data around split polyhedra) are 32-bit, and asking for them past 2^32 "
    "cells is refused before reading "
    "(`PvtuReader.CellOriginsPast32BitsTogetherAreRefusedBeforeReading`). Neighbour references "
    "are an element index shifted past a 2-bit type (the paper's encoding): the 2^31-word bound"
    " above keeps every index below 2^30 - 1 for every type and encoding (a `static_assert` in "
    "prep/prepare.h), and `ShaderIndexRange.*` checks each type at its largest accepted and "
    "smallest refused count. Device buffers are reached through their device addresses, never a"
    " descriptor range: each is checked against the device's `maxBufferSize` (Vulkan 1.3 "
    "maintenance4) and `maxMemoryAllocationSize` (maintenance3) before it is created and before"
    " its memory is allocated (`vk::bufferSizeError`), and refused in one line naming the "
    "buffer, its size, the limit and how many times the ranks would bring it under (lavapipe: 4"
    " GiB - 1 and 2 GiB; tests `BufferLimits.AtEachLimitABufferPassesAndOneByteMoreIsRefused`, "
    "`Vk.BufferPastTheDeviceLimitsIsRefusedBeforeAllocating`). `generate` checks the disk and "
    "memory a mesh needs before it writes anything, and writes pieces to staging names, the "
    "index last (`app.generate-grid`). docs/BENCHMARKS.md (\"Scale\") has the sizes that were "
    "run.\n")


def regressions_section(md):
    md.append("### Bugs the fuzzers found, fixed\n")
    md.append("Each input is committed under tests/fuzz/regressions/TARGET/ and listed in its "
              "index.tsv with the outcome it must now give; "
              "`FuzzRegressions.EveryCommittedInputGivesItsRecordedOutcome` (test_reliability, "
              "label `unit`) replays them through the ordinary entry points in the normal and the"
              " sanitizer build, and ci/fuzz.sh adds them to every fuzzer's corpus.\n")
    md.append("| input | now gives | bug and fix |")
    md.append("|---|---|---|")
    n = 0
    for line in (read(os.path.join(ROOT, "tests/fuzz/regressions/index.tsv")) or "").splitlines():
        if not line or line.startswith("#"):
            continue
        name, outcome, bug = line.split("\t", 2)
        md.append("| `%s` | %s | %s |" % (name, "accepted" if outcome == "accepted"
                                          else "error `…%s…`" % outcome, bug))
        n += 1
    md.append("")
    return n


def sanitize_section(md):
    md.append("## 2. Sanitizer build\n")
    supp = [l.split(":", 1)[1] for l in (read(os.path.join(ROOT, "ci/lsan.supp")) or "")
            .splitlines() if l.startswith("leak:")]
    md.append("`ci/sanitize.sh`: build-asan/ with `-DSHELLMARCH_SANITIZE=address,undefined` "
              "(GCC, `-O1`, Debug: assertions on, `-fno-sanitize-recover=all`), then ctest. "
              "ASan aborts on the first report, UBSan halts on the first.\n")
    md.append("The set in CI: the libraries' `unit` tests (mesh, io, formats, partition, prep, gen, "
              "ref, compositor host logic, shader cache, common; reliability: fuzz regressions and "
              "limits) and the `mpi` tests `CompositorMpi.FailureOnOneRankEndsAllRanks` and "
              "`CompositorMpi.2ranks`. `ci/sanitize.sh --all` adds the command-line tool, the "
              "viewer and their tests (`app.cli-errors`, the viewer's and the app's unit tests, the "
              "fault tests across ranks): they double the sanitizer build and their error tests "
              "take minutes under ASan, which CI's 90-minute limit cannot hold; in CI they run in the"
              " normal build, and the readers they reach are fuzzed. "
              "`CompositorMpi.1ranks`, `3ranks` and `4ranks` and the `gpu`/`image` tests run in"
              " the normal build only: under ASan they cost several times their normal time for "
              "the same device code, and 2 ranks already take every MPI path (exchange, gather, "
              "abort).\n")
    md.append("Leaks: the unit tests run with LeakSanitizer on; ci/lsan.supp suppresses %s only "
              "(third-party lifetime allocations, matched by library name, never by shellmarch "
              "code). Every executable of a sanitizer build carries a `dlclose()` that unloads "
              "nothing (src/common/keep_modules_loaded.cpp, added by "
              "cmake/SanitizerKeepModules.cmake): the Vulkan loader would otherwise unload the "
              "validation layer and the driver before LeakSanitizer reports at exit, leaving "
              "their allocations with no module name to match (`<unknown module>`). "
              "LeakSanitizer's tracer crashed in CI (`Tracer caught signal 11` in "
              "`ScanRangeForPointers`) after `app.cli-errors`'s `--k` command had printed its "
              "error, in 4 full runs of 7 and never when the test was run alone: GCC 12's sanitizer "
              "runtime takes a dynamic TLS block (lavapipe's LLVM and the validation layer have "
              "them) that happens to start 16 bytes into a page for an old glibc block with a "
              "header, and records heap garbage as its range (google/sanitizers#1322, fixed from "
              "GCC 14). The tests therefore run with `intercept_tls_get_addr=0`, which leaves "
              "dynamic TLS unscanned for roots; no test reports a leak for that. "
              "The command-line error tests want exit status "
              "1 exactly (2 for a command line the option parser refuses): before, any non-zero "
              "status passed, a sanitizer's abort (134) after the right message included, so an "
              "error path's leak or memory error went unseen. The `mpi` tests run with "
              "`detect_leaks=0`: Open MPI keeps allocations for the process's life, some made "
              "through libc calls that the fast unwinder cannot walk out of (no Open MPI frame "
              "names them for a suppression), and with the slow unwinder `CompositorMpi.2ranks` "
              "did not finish in 15 minutes. Every other check stays on for them.\n"
              % ", ".join("`%s`" % x for x in supp))
    cases = []
    found = False
    for part in ("unit", "mpi"):
        c = junit(os.path.join(ASAN, "sanitize-%s.xml" % part))
        if c is not None:
            found = True
            cases += c
    st = times(os.path.join(ASAN, "sanitize-times.txt"))
    md.append("### Last run (%s)\n" % mtime(os.path.join(ASAN, "sanitize-mpi.xml")))
    if not found:
        md.append("No results: run `ci/sanitize.sh`.\n")
        return None
    passed = sum(1 for c in cases if c[1])
    skipped = [c[0] for c in cases if c[4]]
    line = "%d of %d tests passed." % (passed, len(cases) - len(skipped))
    if skipped:
        line += " Skipped by the test itself: %s." % ", ".join("`%s`" % n for n in skipped)
    for name, ok, secs, out, skip in cases:
        if not ok and not skip:
            why = first_line(out, r"ERROR: (Address|Leak)Sanitizer|runtime error|FAILED")
            line += " Failed: `%s`%s." % (name, " (%s)" % why if why else "")
    for key, label in (("build", "Build"), ("unit", "Unit tests"), ("mpi", "MPI tests")):
        if key in st:
            line += " %s: %s wall, %s CPU." % (label, minutes(st[key][0]), minutes(st[key][1]))
    slow = sorted(cases, key=lambda c: -c[2])[:4]
    line += " Slowest: %s." % ", ".join("`%s` %.0f s" % (c[0], c[2]) for c in slow)
    md.append(line + "\n")
    md.append("Found by this build and fixed: `sm::Hasher::bytes` passed a null pointer to "
              "`memcpy` when hashing an empty array (cache keys of meshes without some element "
              "type; src/common/hash.cpp), and the compositor tests' reference model took "
              "`&v[i]` of empty fragment vectors (tests/compositor/fragment_model.cpp).\n")
    return passed, len(cases) - len(skipped)


LIMITS = [
    (".vtu", "NumberOfPoints/Cells and every DataArray's tuples x components against the bytes "
     "present (raw, base64 and ascii); appended headers; compressed block tables (count, sizes, sum "
     "against the data and against what zlib, LZ4 or LZMA can expand to; an LZMA block against its "
     ".xz index); a size product guard at 2^60",
     "tests/io/robustness_test.cpp `AbsurdSizesInVtuAreRejectedBeforeAllocating`, "
     "`TruncatedFilesAreErrorsNotCrashes`, `FlippedBytesAreErrorsOrMeshes`"),
    (".pvtu", "each piece is a .vtu with the checks above; the piece count; a piece's declared "
     "cells are only a weight when pieces are shared over ranks",
     "tests/reliability/limits_test.cpp `PvtuPieceDeclaringAbsurdCounts`"),
    ("legacy .vtk", "every count (POINTS, CELLS, CELL_TYPES, POINT_DATA/CELL_DATA, FIELD arrays "
     "and their tuples, LOOKUP_TABLE, component counts up to 4096) against the bytes or tokens "
     "left", "robustness_test `AbsurdSizesInLegacyVtk`; limits_test "
     "`LegacyVtkArraysDeclaringMoreThanTheFileHolds`"),
    (".ugrid", "the 7 counts against the file size (each at most one per byte), the payload they"
     " imply, Fortran record markers (and the 2 GiB sub-record limit)",
     "robustness_test `AbsurdSizesInUgrid`; limits_test `UgridFortranRecordMarkersAndCounts`"),
    ("preparation cache", "each section's count against the bytes left, before allocating; "
     "every index range-checked", "limits_test `CacheSectionsDeclaringMoreThanTheFileHolds` "
     "(with a valid checksum, so that the checksum is not what saves it)"),
    ("colour map JSON", "no declared sizes; nesting depth", "limits_test "
     "`DeeplyNestedColormapJson` (100 000 levels: an error, no stack overflow)"),
]


def limits_section(md):
    md.append("## 3. Limits\n")
    md.append("### Absurd declared sizes\n")
    md.append("Every reader checks a declared size against the bytes actually present before it "
              "allocates. The tests run under a replaced global `operator new` that throws for "
              "any single request over 32 MiB, so believing a size is a test failure, not a slow"
              " test; the fuzzers add `-malloc_limit_mb=256`.\n")
    md.append("| input | checked | tests |")
    md.append("|---|---|---|")
    for row in LIMITS:
        md.append("| %s | %s | %s |" % row)
    md.append("")
    md.append("### Device out of memory\n")
    md.append("`vk::Context` keeps a count of the device memory its buffers hold and refuses an "
              "allocation that would pass `deviceMemoryLimit()`: the largest device-local heap, "
              "or `SHELLMARCH_DEVICE_MEMORY_LIMIT` (bytes, or K/M/G) where that is smaller, the "
              "test hook. `render` turns `vk::DeviceMemoryError` into one line that says what "
              "would fit: for the scene (buffers, shell boxes, BLAS with its build scratch, "
              "sized by the device's own size query) a rank count; for fragment lists a `--k`, "
              "a `--size` and, for two-pass lists, a rank count. The fault tests check that the "
              "suggestions do fit. Messages from the last run:\n")
    for case in ("oom_scene", "oom_lists_fixed", "oom_lists_two_pass"):
        line = first_line(read(os.path.join(FAULTS, case, "small.log")), "out of device memory")
        md.append("- `%s`: %s" % (case, "`%s`" % line if line else "(not run)"))
    md.append("")
    md.append("### 32-bit indices on the device\n")
    md.append(INDEX_LIMITS)
    md.append("### Counts past 32 bits, buffers past the device's limits\n")
    md.append(SCALE_LIMITS)
    md.append("### Fragment overflow\n")
    md.append("Fixed-length lists (`--lists drop|merge --k K`) count every fragment they drop or "
              "merge (`RenderStats.overflow`). `--stats` prints it per frame, `--stats-json` has "
              "`fragment_overflow` per frame and in total, and `render` warns on rank 0 whenever "
              "it is not zero, with or without `--stats`. From the last run:\n")
    log = read(os.path.join(FAULTS, "overflow", "fixed.log"))
    for pat in (r"overflowed", r"overflow [0-9]+;"):
        line = first_line(log, pat)
        md.append("- `%s`" % line if line else "- (not run)")
    md.append("")


def faults_section(md, rel, rel_path):
    md.append("## 4. Faults\n")
    md.append("`SHELLMARCH_FAULT` (src/common/fault_injection.h) makes one rank die (SIGKILL: "
              "nothing of it runs any more, as after a crash or the OOM killer) or fail (an "
              "ordinary `sm::Error`) at the start of a chosen frame, or halfway through writing "
              "an output file under its temporary name. tests/reliability/faults.sh drives the "
              "command-line tool under it, each case a ctest test (`Reliability.CASE`; the "
              "`Reliability.data` fixture generates a 4 857-element capsule in 3 pieces with 3 "
              "time steps). A hang is a `timeout` (240 s), never waited out; the time from the "
              "injected fault (which logs its wall-clock time) to the end of every rank is "
              "measured and must stay under a minute. A third point holds a time step read "
              "ahead (`at=read-ahead,action=stall`) until the reader stops it: the viewer test "
              "`ViewerHeadless.ClosingOrJumpingStopsTheStepReadAhead` closes the viewer, and "
              "jumps to another step, while such a read runs, and must end at once with both "
              "reads stopped (`io::ReadOptions::stopRequested`) instead of waiting for them. A "
              "fourth makes the viewer's window ask to close as a new field's colour range pass "
              "starts (`at=range-pass,action=close`): "
              "`ViewerHeadless.ClosingDuringANewFieldsRangePassStopsIt` must end before the pass "
              "reads a step, on one rank and on two (rank 1 learns of it through the pass's "
              "collective); with `action=next-field` the field key is pressed then instead, and "
              "`ViewerHeadless.TheFieldKeyDuringARangePassGoesOnWithoutIt` must go on to the "
              "next field without reading a step of the one left.\n")
    md.append("Every output (PNG, cache, .vtu/.pvtu, statistics JSON) goes through "
              "`sm::writeFileAtomically`: written under `NAME.tmp.PID.N` and renamed when "
              "complete, so a name never holds a partial file. A process killed mid-write leaves"
              " its temporary behind (nothing can remove it); an error removes it.\n")
    md.append("### Last run (%s)\n" % mtime(rel_path))
    by_name = {c[0]: c for c in (rel or [])}
    md.append("| test | label | fault injected | checked | result |")
    md.append("|---|---|---|---|---|")
    passed = 0
    for case, label, fault, checked in FAULT_CASES:
        c = by_name.get("Reliability." + case)
        if c is None:
            result = "not run"
        else:
            detail = (read(os.path.join(FAULTS, case, "result.txt")) or "").strip()
            m = re.search(r"passed \((.*)\)$", detail) if c[1] else re.search(r"FAILED: (.*)",
                                                                                detail)
            result = ("passed" if c[1] else "**FAILED**") + (": " + m.group(1) if m else "")
            result += " (%.0f s)" % c[2]
            passed += c[1]
        md.append("| `Reliability.%s` | %s | %s | %s | %s |" % (case, label, fault, checked,
                                                             result))
    md.append("")
    return passed


# Measured apart from ci/test.sh, which reuses build/ (a fresh CI machine's first run builds from
# clean); rerun the command in the text and update the figures when the build changes much.
CLEAN_BUILD = """\
A clean build, as on a fresh machine, is measured apart (AMD EPYC, 2 cores, shared with other builds: load average 3.6 on average, 2.2 to 5.1, during the build):

    rm -rf /tmp/cleanbuild
    cmake -S . -B /tmp/cleanbuild -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHELLMARCH_BUILD_TESTS=ON
    time ninja -C /tmp/cleanbuild -j 2 shellmarch    # what ci/demo.sh builds
    time ninja -C /tmp/cleanbuild -j 2               # the rest, which ci/test.sh builds too

| clean build | wall | CPU | 2-core estimate |
|---|---:|---:|---:|
| `shellmarch` only (ci/demo.sh) | 9 min 21 s | 11 min 24 s | 5 min 42 s |
| everything (ci/build.sh) | 18 min 33 s | 23 min 10 s | 11 min 35 s |

The 24 shaders are embedded in C++ by tools/spv_embed, in about 1 s together. The CMake script it replaced took time growing with the square of a shader's size: 3 min 10 s of CPU for tracer.spv (58 549 words), about 11.5 min for the four large render shaders, in each build folder that compiles them (build/ and the sanitizer build's). With it a clean build of everything took about 25 min on this machine, and the last full CI run from a clean clone 4146 s in all.
"""


TEST_TIME = """\
Where the tests' time goes (measured 2026-12-02, `ctest -j 2`, 726 tests, 2058 s wall, 62 min of CPU): a process that renders under the validation layer compiles its pipelines from SPIR-V each time (3.7 s for the tracer on one core; Debian 12's layer, 1.3.239, predates `VK_EXT_shader_object`, so the shader binaries the cache keeps for runs without validation cannot be used, and lavapipe's `VkPipelineCache` keeps nothing). That is about 40% of an image test's CPU (`ImageVsReference.ConstantFieldMapsToTheTablesMiddle`: 14.4 s with validation, 7.9 s without) and most of the command-line scripts' (one compile per rank per render). The scripts that run `mpiexec` hold the `mpi` resource lock one after another, about 25 minutes together; their `COST` properties start them first on a clean clone, beside the rest.
"""


def ci_section(md, fuzz_ok, asan):
    md.append("## 5. Time in CI\n")
    ct = times(os.path.join(BUILD, "ci-times.txt"))
    md.append("`ci/test.sh` (the CI entry point) records each step in build/ci-times.txt. The "
              "machine these numbers come from is shared with other builds, so wall time "
              "overstates what a dedicated 2-core runner takes; CPU time (user + system) / 2 is "
              "the estimate for one, except for fuzzing, whose time is fixed.\n")
    if not ct:
        md.append("No full CI run recorded: run `ci/test.sh`.\n")
        md.append(TEST_TIME)
        md.append(CLEAN_BUILD)
        return
    md.append("| step | wall | CPU | 2-core estimate |")
    md.append("|---|---:|---:|---:|")
    est_total = wall_total = 0
    fuzz_fixed = sum(w for k, (w, c) in times(os.path.join(FUZZ, "fuzz-times.txt")).items()
                     if k.startswith("fuzz_"))
    for key, label in (("build", "build (Release)"), ("tests", "ctest, every test"),
                       ("fuzz", "ci/fuzz.sh"), ("sanitize", "ci/sanitize.sh")):
        if key not in ct:
            continue
        wall, cpu = ct[key]
        est = cpu / 2
        if key == "fuzz" and fuzz_fixed:  # two fuzzers at a time
            est = fuzz_fixed / 2 + max(0.0, cpu - fuzz_fixed) / 2
        est_total += est
        wall_total += wall
        md.append("| %s | %s | %s | %s |" % (label, minutes(wall), minutes(cpu), minutes(est)))
    md.append("| **total** | %s | | %s |" % (minutes(wall_total), minutes(est_total)))
    md.append("")
    md.append(TEST_TIME)
    md.append(CLEAN_BUILD)


def main():
    out = sys.argv[1]
    md = []
    now = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    cpu = first_line(read("/proc/cpuinfo"), r"^model name") or "model name: ?"
    load = (read("/proc/loadavg") or "? ? ?").split()[:3]
    md.append("# Reliability: bad input and faults\n")
    md.append("*Generated by `ci/reliability-report.sh` (runs the fuzzers, the sanitizer build "
              "and the fault tests, then writes this file) or `ci/reliability-report.sh "
              "--no-run` (rewrites it from the last results in build-fuzz/, build-asan/ and "
              "build/). Do not edit by hand. Written %s on %s, %d cores, load average %s.*\n"
              % (now, cpu.split(":", 1)[1].strip(), os.cpu_count(), " ".join(load)))
    md.append("shellmarch reads other people's files and runs on many ranks: it must fail loudly "
              "and cleanly, never crash, hang or leave half an output. This is what is fuzzed, "
              "which faults are injected, and what came out.\n")
    body = []
    fuzz = fuzz_section(body)
    nreg = regressions_section(body)
    asan = sanitize_section(body)
    # The fault tests' results: from ci/reliability-report.sh's own run or ci/test.sh's, whichever
    # is newer.
    runs = [p for p in (os.path.join(BUILD, "reliability.xml"), os.path.join(BUILD, "ctest.xml"))
            if os.path.exists(p)]
    rel_path = max(runs, key=os.path.getmtime) if runs else os.path.join(BUILD, "reliability.xml")
    rel = junit(rel_path)
    if rel is not None:
        rel = [c for c in rel if c[0].startswith("Reliability.")] or None
    limits_section(body)
    nfault = faults_section(body, rel, rel_path)
    ci_section(body, fuzz, asan)
    md.append("| | result |")
    md.append("|---|---|")
    md.append("| fuzzing | %s |" % ("not run" if not fuzz else "%d executions over %d targets, "
              "%s" % (fuzz[0], len(TARGETS), "no findings" if not fuzz[1] else
                      "**findings in %s**" % ", ".join(fuzz[1]))))
    md.append("| bugs found and fixed | %d, each with a regression input |" % nreg)
    md.append("| sanitizer build (unit + MPI tests) | %s |" % (
        "not run" if not asan else "%d of %d passed" % asan))
    md.append("| fault tests | %s |" % ("not run" if rel is None else "%d of %d passed" % (
        nfault, len(FAULT_CASES))))
    md.append("")
    md.extend(body)
    with open(out, "w") as f:
        f.write("\n".join(md).rstrip() + "\n")


if __name__ == "__main__":
    main()
