"""Modules that are also their main function: ``pamkit.simulate(...)`` and ``pamkit.diagnose(...)``.

``pamkit.simulate`` and ``pamkit.diagnose`` were modules before they were functions, and code
imports from them (``from pamkit.simulate import simulate_experiment``, ``import
pamkit.diagnose.engine as engine``). Binding the package's attribute to a function instead
would break the second form (``import a.b.c as d`` looks ``b`` up as an attribute of ``a``),
and the import system would rebind the attribute to the module whenever the submodule is
first imported after the package. So the module stays the module, and calling it calls its
main function; ``help()`` on it shows the module's docstring, which describes the call first.
"""

from __future__ import annotations

import inspect
import sys
import types
from collections.abc import Callable


class CallableModule(types.ModuleType):
    """A module whose call is its ``__main_function__``."""

    def __call__(self, *args, **kwargs):
        return self.__main_function__(*args, **kwargs)


def make_callable(module_name: str, function: Callable) -> None:
    """Makes the (imported) module `module_name` callable as `function`, with its signature."""
    module = sys.modules[module_name]
    module.__main_function__ = function
    module.__signature__ = inspect.signature(function)
    module.__class__ = CallableModule
