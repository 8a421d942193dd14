"""Data: the labelled netCDF cubes (xarray), the parameter cache, and the data files
(the paper's printed values, materials)."""
