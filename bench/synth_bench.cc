// Time per frame of the synthetic sequence generator, stage by stage (one core):
//   bin/bench_synth --benchmark_filter=Synth
#include <benchmark/benchmark.h>

#include <filesystem>

#include "amos/synth/png_writer.h"
#include "amos/synth/random.h"
#include "amos/synth/sequence.h"

namespace {

using amos::synth::SequenceGenerator;

const SequenceGenerator& walkingXyz() {
  static const SequenceGenerator generator([] {
    amos::synth::SequenceOptions o;
    o.preset = "walking_xyz";
    o.seed = 1;
    return o;
  }());
  return generator;
}

void BM_SynthSetup(benchmark::State& state) {
  amos::synth::SequenceOptions o;
  o.preset = "walking_xyz";
  for (auto _ : state) {
    SequenceGenerator g(o);
    benchmark::DoNotOptimize(g.frameCount());
  }
}
BENCHMARK(BM_SynthSetup)->Unit(benchmark::kMillisecond)->Iterations(2);

void BM_SynthRenderDepthAndMask(benchmark::State& state) {
  const SequenceGenerator& g = walkingXyz();
  int k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(g.renderExact(k++ % 300, true, true, false).depth.data);
}
BENCHMARK(BM_SynthRenderDepthAndMask)->Unit(benchmark::kMillisecond);

void BM_SynthRenderWithColour(benchmark::State& state) {
  const SequenceGenerator& g = walkingXyz();
  int k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(g.renderExact(k++ % 300, true, true, true).color.data);
}
BENCHMARK(BM_SynthRenderWithColour)->Unit(benchmark::kMillisecond);

void BM_SynthFrame(benchmark::State& state) {  // render + sensor model + moving flags
  const SequenceGenerator& g = walkingXyz();
  int k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(g.render(k++ % 300).bgr.data);
}
BENCHMARK(BM_SynthFrame)->Unit(benchmark::kMillisecond);

void BM_SynthWritePngs(benchmark::State& state) {
  const amos::synth::SyntheticFrame f = walkingXyz().render(100);
  const auto dir = std::filesystem::temp_directory_path();
  for (auto _ : state) {
    amos::synth::writePng((dir / "amos_bench_rgb.png").string(), f.bgr);
    amos::synth::writePng((dir / "amos_bench_depth.png").string(), f.depth_raw);
    amos::synth::writePng((dir / "amos_bench_mask.png").string(), f.mask);
  }
}
BENCHMARK(BM_SynthWritePngs)->Unit(benchmark::kMillisecond);

}  // namespace
