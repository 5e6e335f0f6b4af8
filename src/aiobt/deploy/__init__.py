"""Deploying across hosts: certificates for mutual TLS and the Zenoh configs that use them.

See docs/deployment.md; the access-control rules live in deploy/access-control.json5.
"""
