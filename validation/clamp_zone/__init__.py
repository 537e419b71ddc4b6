"""The clamp-zone study: where and at which charge the clamped Keplinger plate first
buckles, unit by unit (one weight fraction on one graded mesh), and what the mesh, the
pressure space and the clamp edge say about it.

One command runs it, ``skfem-dielectric clamp-zone SUBCOMMAND`` (:mod:`validation.clamp_zone.cli`); its
tables are listed in :data:`validation.data.registry.TABLES` and read by :func:`validation.data.registry.load`; docs/clamp-zone.md
says what a unit is and how to run one on a laptop or a dask cluster.

* :mod:`validation.data.key` -- :class:`~validation.data.key.UnitKey`, what names a unit;
* :mod:`validation.data.spec`, :mod:`validation.store.tables` -- a table's columns and
  reading it back; writing it under its lock;
* :mod:`validation.data.registry` -- the tables by name, :func:`~validation.data.registry.load`, the convergence rule of a load;
* :mod:`validation.clamp_zone.units`, :mod:`validation.clamp_zone.onsets`, :mod:`validation.clamp_zone.p33`, :mod:`validation.clamp_zone.layer`, :mod:`validation.clamp_zone.flagged`,
  :mod:`validation.clamp_zone.counts`, :mod:`validation.clamp_zone.section` -- one runner per analysis;
* :mod:`validation.clamp_zone.local_theory`, :mod:`validation.clamp_zone.scaling` -- the closed forms at a point of the plate and the
  wavelength's scaling;
* :mod:`validation.clamp_zone.tables`, :mod:`validation.clamp_zone.modes`, :mod:`validation.clamp_zone.band` -- the Markdown tables and the figures.

Importing this package loads no finite elements.
"""
