"""Interface types: read from template arguments, callbacks, aliases and variables.

A type alias of the file (``using NavigateToPose = nav2_msgs::action::NavigateToPose;``,
``typedef``) is replaced by what it stands for, as is a name a using-declaration brings
in (``using std_srvs::srv::SetBool;``). A using-directive (``using namespace
std_srvs::srv;``) names no type: what it brings in is left as spelled.

The message and service types of roscpp's untemplated calls come from the callbacks a
subscriber or server is given.

roscpp infers the type of ``nh.subscribe("chatter", 10, chatterCallback)`` from the
callback's parameter (``const std_msgs::String::ConstPtr& msg``) and that of
``nh.advertiseService("add_two_ints", add)`` from ``add``'s ``Request``/``Response``
parameters. The callback may be a function or method of the same file (by name, ``&cb``,
``&Class::cb``, ``boost::bind(&Class::cb, this, _1)``) or a lambda. Types are returned as
spelled, without the pointer and event wrappers around them (``boost::shared_ptr<const
T>``, ``T::ConstPtr``, ``ros::MessageEvent<T const>``): the message or service type.
"""

from __future__ import annotations

import re

from tree_sitter import Node

from .source import Source, arguments, compact, enclosing, unparenthesized

_BINDERS = frozenset({"boost::bind", "std::bind", "bind"})
_WRAPPER = re.compile(
    r"(?:boost::|std::)?(?:shared_ptr|unique_ptr)<(.*)>|"
    r"(?:ros::)?(?:MessageEvent|ServiceEvent)<(.*)>|const (.*)|(.*) const"
)
_POINTER_SUFFIX = re.compile(r"(?:::(?:ConstPtr|Ptr|SharedPtr|ConstSharedPtr|UniquePtr)|ConstPtr)$")
_SERVICE_PART = re.compile(r"(?:::)?(Request|Response)$")
_CLASSES = frozenset({"class_specifier", "struct_specifier"})
_MAX_PARTS = 2  # ServiceEvent<Request, Response>: the first part names the service


class Types:
    """Interface types the file spells, resolved through its aliases and callbacks."""

    def __init__(self, source: Source) -> None:
        self._source = source

    def resolve(self, spelling: str) -> str:
        """``NavigateToPose`` -> ``nav2_msgs::action::NavigateToPose`` when the file says so."""
        if not re.fullmatch(r"[A-Za-z_]\w*", spelling):
            return spelling
        targets = {
            compact(self._source.text(target))
            for word in self._source.occurrences(spelling)
            if (target := _aliased(word)) is not None
        }
        return targets.pop() if len(targets) == 1 else spelling

    def declared_type(self, declarations: list[Node]) -> str | None:
        """The type a variable is declared with: ``beginner_tutorials::AddTwoInts srv;``."""
        spellings = set()
        for declaration in declarations:
            kind = declaration.child_by_field_name("type")
            if kind is not None and kind.type != "placeholder_type_specifier":
                spellings.add(self.resolve(compact(self._source.text(kind))))
        return spellings.pop() if len(spellings) == 1 else None

    def message_type(self, callback: Node) -> str | None:
        """The message type of a subscriber callback's first parameter."""
        parameters = self._parameters(callback)
        message = _message(parameters[0]) if parameters else None
        return None if message is None else self.resolve(message)

    def service_type(self, callback: Node) -> str | None:
        """The service of the first ``Request``/``Response`` parameter."""
        for parameter in self._parameters(callback) or []:
            message = _message(parameter)
            if message is not None and _SERVICE_PART.search(message):
                service = _SERVICE_PART.sub("", message)
                return self.resolve(service) if service else None
        return None

    def _parameters(self, callback: Node) -> list[str] | None:
        node = _target(self._source, callback)
        if node is None:
            return None
        if node.type == "lambda_expression":
            declarator = node.child_by_field_name("declarator")
            return self._parameter_types(
                None if declarator is None else declarator.child_by_field_name("parameters")
            )
        scope, name = _split_name(self._source, node)
        if name is None:
            return None
        candidates = {
            tuple(types)
            for parameters in self._declared_parameters(name, scope)
            if (types := self._parameter_types(parameters))
        }
        return list(candidates.pop()) if len(candidates) == 1 else None

    def _declared_parameters(self, name: str, scope: str | None) -> list[Node]:
        """Parameter lists of the functions named ``name`` (in class ``scope`` if given)."""
        found = []
        for word in self._source.occurrences(name):
            declarator, owner = word.parent, None
            if declarator is not None and declarator.type == "qualified_identifier":
                qualifier = declarator.child_by_field_name("scope")
                owner = None if qualifier is None else self._source.text(qualifier)
                declarator = declarator.parent
            if declarator is None or declarator.type != "function_declarator":
                continue
            if owner is None:
                owner = self._class_of(declarator)
            if scope is not None and owner is not None and owner != scope:
                continue
            parameters = declarator.child_by_field_name("parameters")
            if parameters is not None:
                found.append(parameters)
        return found

    def _class_of(self, node: Node) -> str | None:
        owner = enclosing(node, _CLASSES)
        name = None if owner is None else owner.child_by_field_name("name")
        return None if name is None else self._source.text(name)

    def _parameter_types(self, parameters: Node | None) -> list[str]:
        types = []
        for parameter in arguments(parameters):
            kind = parameter.child_by_field_name("type")
            if kind is None:
                return []
            types.append(compact(self._source.text(kind)))
        return types


def _aliased(word: Node) -> Node | None:
    """The type an alias declaration gives ``word``, if ``word`` is the alias's name, or
    the qualified name a using-declaration brings ``word`` in by."""
    parent = word.parent
    if parent is None:
        return None
    if parent.type == "alias_declaration" and parent.child_by_field_name("name") == word:
        return parent.child_by_field_name("type")
    if parent.type == "type_definition" and word in parent.children_by_field_name("declarator"):
        return parent.child_by_field_name("type")
    # ``std_srvs::srv::SetBool`` nests as std_srvs::(srv::SetBool): up through the names.
    named: Node = word
    while parent is not None and parent.type == "qualified_identifier":
        if parent.child_by_field_name("name") != named:
            return None
        named, parent = parent, parent.parent
    if named is word or parent is None or parent.type != "using_declaration":
        return None
    if any(child.type == "namespace" for child in parent.children):
        return None  # ``using namespace``: no type
    return named


def _target(source: Source, callback: Node) -> Node | None:
    """What a callback argument designates: a name or a lambda, through binds and ``&``."""
    node = unparenthesized(callback)
    if node.type == "call_expression":
        callee = node.child_by_field_name("function")
        bound = arguments(node.child_by_field_name("arguments"))
        if callee is None or compact(source.text(callee)) not in _BINDERS or not bound:
            return None
        node = unparenthesized(bound[0])
    if node.type == "pointer_expression":
        inner = node.child_by_field_name("argument")
        if inner is None:
            return None
        node = inner
    if node.type in ("identifier", "qualified_identifier", "lambda_expression"):
        return node
    return None


def _split_name(source: Source, node: Node) -> tuple[str | None, str | None]:
    """``Class::method`` -> ("Class", "method"); ``callback`` -> (None, "callback")."""
    if node.type == "identifier":
        return None, source.text(node)
    scope = node.child_by_field_name("scope")
    name = node.child_by_field_name("name")
    if name is None or name.type != "identifier":
        return None, None
    return (None if scope is None else source.text(scope)), source.text(name)


def _message(spelling: str) -> str | None:
    """``const boost::shared_ptr<const std_msgs::String>`` -> ``std_msgs::String``."""
    text = spelling.strip()
    for _ in range(8):  # wrappers nest a few levels at most
        match = _WRAPPER.fullmatch(text)
        if match is None:
            break
        inner = next(group for group in match.groups() if group is not None)
        text = inner.split(",", _MAX_PARTS - 1)[0].strip() if "<" not in inner else inner.strip()
    text = _POINTER_SUFFIX.sub("", text)
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_:]*", text):
        return None
    return text
