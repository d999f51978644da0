"""The application layer: the ``springdyn`` command (:mod:`springdyn.app.cli`) and the
HTML report (:mod:`springdyn.app.report`).

It chooses inputs, calls the library and formats what comes back; it holds no physics
and no numbers of its own, and the physics packages never import it.
"""
