"""Synthetic bench tests: the thesis's instruments on their own clocks (`instruments`) and datasets
with one catalog effect hidden in them (`dataset`, `pamkit synth`)."""
