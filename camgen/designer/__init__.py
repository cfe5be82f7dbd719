"""The designer in the browser (``camgen serve``): a local web app that edits one template per browser tab and
answers every edit with the project's own design code (:mod:`camgen.api`, :mod:`linkgen.api`).

:mod:`camgen.designer.session` is one tab's design (pure Python: no server library), :mod:`camgen.designer.form`
the form read from the template models, :mod:`camgen.designer.views` what is drawn, :mod:`camgen.designer.app` the
Starlette app and :mod:`camgen.designer.serve` the server (both import the optional ``serve`` extra lazily).
"""
