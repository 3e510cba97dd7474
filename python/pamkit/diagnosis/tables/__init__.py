"""The diagnosis of static tables (isometric maps, isotonic tests, free-inflation tables, and a
supplied cyclic test of the same muscle among them): their units and noise (kinds), the fit of
their model (fit), the candidates and the decision (engine), what is left as physical terms
(discover) and the report (report). The stages shared with the time series sit beside this
package."""
