"""The columns of a measured time series: their names, and which instrument records them."""

from __future__ import annotations

from pamkit._core import measured_channels

# The time base and the crosshead's motion are required; the channels the instruments read
# (declared once, in C++: effect.hpp's measured_channels) are optional. Every module that lists
# them imports them from here.
REQUIRED_COLUMNS = ("time_s", "elongation_m")
OPTIONAL_COLUMNS = tuple(measured_channels())
SERIES_COLUMNS = REQUIRED_COLUMNS + OPTIONAL_COLUMNS
# The channels the Arduino logger records (the 61CP transducer on A0, the TMP36 on A1); the
# tensile machine records the others.
LOGGER_CHANNELS = ("pressure_kPa", "temperature_C")
