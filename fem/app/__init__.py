"""The outer room of the package: the ``drivefem`` command line (one function per command),
the demo and the Dask sweep driver."""
