"""A second, independent implementation of a braided (McKibben) muscle on a bench, for tests that
hide a cause in measured data. Nothing here imports pamkit: the physics is derived afresh
(:mod:`.physics`), the instruments are re-stated from the thesis's appendix B (:mod:`.bench`),
and the families of :mod:`.families` write experiments (TOML + CSV) that reach pamkit only
through files, as a user's would."""
