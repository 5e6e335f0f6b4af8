"""AMCL params files shipped with the service (``--params-file NAME``)."""
