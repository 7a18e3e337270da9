"""tools/bench/run: the benchmark runner (scenarios -> out/bench/results.json -> docs/RESULTS.md)."""
