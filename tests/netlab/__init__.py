"""Hosts in network namespaces and a link between them that misbehaves: for tests and
benches of a deployment across hosts (docs/deployment.md)."""
