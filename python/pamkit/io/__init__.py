"""Files in and out: experiment files (their schema in :mod:`~pamkit.io.schema`, their loading in
:mod:`~pamkit.io.experiment`, the muscle's sections in :mod:`~pamkit.io.sections`, the CSV readers
in :mod:`~pamkit.io.series`, the writers in :mod:`~pamkit.io.writers`, the one conversion between a
file's units and SI in :mod:`~pamkit.io.columns`, the checks on whatever is read in
:mod:`~pamkit.io.guards`), tensile machines' exports (Instron Bluehill, ZwickRoell testXpert) and
the Arduino logger's host side."""
