"""Files in and out: experiment files (their schema in :mod:`~pamkit.io.schema`, their loading in
:mod:`~pamkit.io.experiment`, the muscle's sections in :mod:`~pamkit.io.sections`, what each kind
of test reads in :mod:`~pamkit.io.series`, the CSV reader under it in
:mod:`~pamkit.io.csv_reader`, the writers in :mod:`~pamkit.io.writers`, the one conversion between
a file's units and SI in :mod:`~pamkit.io.columns`, the checks on whatever is read in
:mod:`~pamkit.io.guards`), tensile machines' exports (Instron Bluehill, ZwickRoell testXpert) and
the Arduino logger's host side."""
