#!/usr/bin/env python3
"""Where `prm pack`'s CPU goes, by stage, from a `perf script` of a call-graph profile (issue 21).

    taskset -c 1 perf record -F 250 --call-graph dwarf,32768 -o pack.data \\
        build/tools/prm/prm pack ../shared/meshes/venus.off --target-error 1.3e-4 --effort 0 -o out.prm
    perf script -i pack.data > pack.script
    bench/pack_perf_stages.py pack.script

One core (taskset), so that the work of oneTBB's tasks runs on the calling thread and its stacks reach pack's
frames. Each sample goes to the innermost frame that names a stage below; Metro's samples (`one_sided`, the sample
plans) are split by who asked: the remesher's grid search, or the heights' lambda bisection and the full-density
check (told apart only where the compiler did not inline the bisection's measurement).
Prints the share of the samples per stage, largest first. Exit code 1 on a bad command line, an unreadable file or one without call-graph samples.
"""
import collections
import sys

STAGES = ['fit_heights', 'optimize_seams', 'resample_relief', 'slice_relief', 'separate_quantized_vertices',
          'merge_reliefs', 'make_generic', 'one_sided', 'SamplePlan::SamplePlan', 'encode_prm', 'codec::decode',
          'build_reliefs', 'AabbTree::AabbTree', 'count_coincident', 'count_zero_area', 'validate_mesh', 'read_mesh',
          'general_floor', 'to_mesh', 'resample_and_merge', 'remesh::remesh']
METRO = ('one_sided', 'SamplePlan::SamplePlan')


def stage_of(stack):
    """stack: the sample's frames, innermost first."""
    for frame in stack:
        for s in STAGES:
            if s in frame:
                return s + (metro_caller(stack) if s in METRO else '')
    return 'other'


def metro_caller(stack):
    for frame in stack:
        if 'ErrorEstimate (prm::remesh::PrmMesh const&)' in frame:
            return ' (grid search)'
        if 'encode_and_measure' in frame or ('pack_at' in frame and 'codec::PrmOptions const&' in frame):
            return ' (lambda bisection)'
        if 'finish_at' in frame or 'pack_at' in frame:
            return ' (lambda bisection and full-density check)'  # finish_at inlines the bisection's measurements
    return ''


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 1
    try:
        lines = open(sys.argv[1], errors='replace').read().split('\n')
    except OSError as e:
        print(f'pack_perf_stages.py: {e}', file=sys.stderr)
        return 1
    counts = collections.Counter()
    stack = []
    for line in lines + ['']:
        if line.strip() == '':
            if stack:
                counts[stage_of(stack)] += 1
            stack = []
        elif line.startswith((' ', '\t')):
            stack.append(line.strip())
    total = sum(counts.values())
    if total == 0:
        print(f'pack_perf_stages.py: no call-graph samples in {sys.argv[1]} (perf record -g or --call-graph)',
              file=sys.stderr)
        return 1
    for stage, n in counts.most_common():
        print(f'{100.0 * n / total:5.1f}%  {stage}')
    print(f'{total} samples')
    return 0


if __name__ == '__main__':
    sys.exit(main())
