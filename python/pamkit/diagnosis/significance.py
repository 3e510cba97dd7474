"""The thresholds a cause's held-out gain and information criterion are held to, and the noise within
which a model explains the data: one yardstick for a time series (series/decide.py) and a static
table (tables/engine.py). docs/diagnosis.md gives the measurements behind each."""

# 0.03 is ten times what fitting extra parameters to noise gains on held-out cycles (a few
# tenths of a percent on pamkit's null benchmark).
MIN_GAIN = 0.03
# "Very strong" evidence after Kass and Raftery (1995): BIC down by more than 10.
MIN_BIC_DROP = 10.0
BOOTSTRAP_SAMPLES = 1000
# `none` needs every channel's held-out RMSE within this factor of its estimated noise. On
# pamkit's own null benchmark (seeds 1000-1011) the calibrated baseline reaches 0.75-1.52x: the
# noise estimate (a local cubic's median residual) misses part of the noise of channels read on
# another instrument's clock and interpolated, by up to half. Twice the noise leaves a model
# error of at most sqrt(3) sigma unexplained, and is not reached by any null.
NONE_WITHIN_NOISE = 2.0
