"""One builder per kind of model file: typed tables in, the package's models and problems out."""
