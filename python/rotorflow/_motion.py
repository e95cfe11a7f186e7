"""The results of ``simulate`` and ``exact``: dicts with exactly the keys of
``rotorflow simulate --json`` that a notebook shows as the animation of the body turning."""

import functools
import html

from . import _rotorflow


class Motion(dict):
    """The keys of ``rotorflow simulate --json`` (``dim``, ``planes``, ``times``, ``omega``,
    ``momentum``, ``energy``, ``casimirs``, ``attitude``, ``drift``), numbers as arrays; the
    body it moved is kept beside them, as the attribute ``body``, for the animation."""

    __slots__ = ("body",)

    def __init__(self, data, body):
        super().__init__(data)
        self.body = body

    def html(self, title=None):
        """The self-contained HTML page of the animation (play, time slider, drag to turn)."""
        return animation_html(self, title=title)

    def _repr_html_(self):
        """The animation inline in a notebook (the page in an iframe of its own)."""
        page = html.escape(self.html(), quote=True)
        return f'<iframe srcdoc="{page}" style="width: 100%; height: 520px; border: none"></iframe>'

    def __reduce__(self):
        # A body given as a SPEC travels with the numbers; a Body object (which does not
        # pickle) leaves a plain dict of them.
        if isinstance(self.body, str):
            return (Motion, (dict(self), self.body))
        return (dict, (dict(self),))


def animation_html(result, body=None, *, title=None):
    """The crate's HTML animation of a ``simulate`` or ``exact`` result: ``body`` (a ``Body``
    or a SPEC) turning through ``result["attitude"]`` at ``result["times"]``. A result of
    ``rotorflow.simulate`` knows its body; a plain dict with those keys needs ``body``."""
    if body is None:
        body = getattr(result, "body", None)
    if body is None:
        raise ValueError("animation_html: give the body (a Body or a SPEC) that the result moved")
    return _rotorflow.motion_html(body, result["times"], result["attitude"], title=title)


@functools.wraps(_rotorflow.simulate)
def simulate(body, **options):
    return Motion(_rotorflow.simulate(body, **options), body)


@functools.wraps(_rotorflow.exact)
def exact(body, **options):
    return Motion(_rotorflow.exact(body, **options), body)
