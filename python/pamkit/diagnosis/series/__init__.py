"""The diagnosis of a time series (a bench test with a time axis, sealed or supplied, and a
campaign of them): its units and checks (kinds), the model behind a fit (model, motion), the
baseline's calibration and its Jacobians (calibrate, jacobian), the candidate effects
(candidates), the decision and what a fit's parameters say (decide, findings), a campaign of tests
(campaign, joint) and the record of what was found (result). The engine that runs these stages is
pamkit.diagnosis.engine; the stages shared with the tables sit beside this package."""
