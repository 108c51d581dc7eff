"""Instance attributes whose value is certain: ``self.topic`` set in ``__init__`` (or
``cls.topic`` in ``setUpClass``) and used in another method.

An attribute is followed when every write the module makes to it is a plain assignment
through a method's ``self``/``cls`` (or a class-body binding), in its class or a class
related to it by inheritance in the module, and all of them give the same static value.
A write through anything else (``args.topic = ...``, ``self.topic += ...``, a tuple
target, ``del``) makes every attribute of that name unknown: the module may change it.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import libcst as cst

from roslint_names.extract.python.scope import AssignSite, Binding, ClassSite, Scope, ScopeKind


@dataclass
class InstanceAttributes:
    """Every write of every instance attribute of the module's classes."""

    # (class family, attribute) -> its writes, as bindings: the value written (None for
    # anything but a plain expression) and the scope it is evaluated in. A family is the
    # classes related by inheritance.
    writes: dict[tuple[int, str], list[Binding]] = field(default_factory=dict)
    families: dict[cst.ClassDef, int] = field(default_factory=dict)
    unknown: set[str] = field(default_factory=set)

    @classmethod
    def of(
        cls,
        classes: Iterable[ClassSite],
        assignments: Iterable[AssignSite],
        unknown: Iterable[str],
    ) -> InstanceAttributes:
        sites = list(classes)
        found = cls(families=_families(sites), unknown=set(unknown))
        for site in sites:
            for name, bindings in site.body.bindings.items():
                for binding in bindings:
                    found._add(site.node, name, binding)
        for assignment in assignments:
            name = assignment.target.attr.value
            owner = instance_class(assignment.target.value, assignment.context.scope)
            if owner is None:
                found.unknown.add(name)
            else:
                scope = assignment.context.scope
                found._add(owner, name, Binding(scope, value=assignment.value))
        return found

    def of_instance(self, owner: cst.ClassDef, name: str) -> list[Binding]:
        """The writes that may give ``self.name`` its value; empty when unknown."""
        if name in self.unknown:
            return []
        return self.writes.get((self.families.get(owner, id(owner)), name), [])

    def _add(self, owner: cst.ClassDef, name: str, write: Binding) -> None:
        key = (self.families.get(owner, id(owner)), name)
        self.writes.setdefault(key, []).append(write)


def instance_class(expr: cst.BaseExpression, scope: Scope) -> cst.ClassDef | None:
    """The class whose instance (or class object) ``expr`` is: a method's first parameter,
    ``self`` or ``cls``, seen from the method or a comprehension in it."""
    if type(expr) is not cst.Name:
        return None
    assert isinstance(expr, cst.Name)
    while scope.kind is ScopeKind.COMPREHENSION and scope.parent is not None:
        scope = scope.parent
    function = scope.function
    if scope.kind is not ScopeKind.FUNCTION or scope.owner is None or function is None:
        return None
    parameters = (*function.params.posonly_params, *function.params.params)
    if not parameters or parameters[0].name.value != expr.value:
        return None
    if any(_is_staticmethod(decorator.decorator) for decorator in function.decorators):
        return None
    return scope.owner


def _is_staticmethod(decorator: cst.BaseExpression) -> bool:
    return isinstance(decorator, cst.Name) and decorator.value == "staticmethod"


def _families(sites: list[ClassSite]) -> dict[cst.ClassDef, int]:
    """Classes of the module joined with the module's classes they derive from, by name."""
    family = {site.node: index for index, site in enumerate(sites)}
    by_name: dict[str, list[cst.ClassDef]] = {}
    for site in sites:
        by_name.setdefault(site.node.name.value, []).append(site.node)
    changed = True
    while changed:  # a handful of classes per module: joining until stable is cheap
        changed = False
        for site in sites:
            for base in site.node.bases:
                name = _last_name(base.value)
                for parent in by_name.get(name or "", []):
                    low = min(family[parent], family[site.node])
                    for node, current in family.items():
                        if current in (family[parent], family[site.node]) and current != low:
                            family[node] = low
                            changed = True
    return family


def _last_name(expr: cst.BaseExpression) -> str | None:
    if isinstance(expr, cst.Name):
        return expr.value
    if isinstance(expr, cst.Attribute):
        return expr.attr.value
    return None
