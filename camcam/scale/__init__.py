"""Running many independent tasks in this process or on a Dask cluster."""
