# SPDX-License-Identifier: AGPL-3.0-or-later
"""The add-on's preferences: which DOT server to use."""
import bpy
from bpy.props import BoolProperty, FloatProperty, StringProperty

from . import connection


class DotPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    server_address: StringProperty(
        name="Server", default="",
        description="host:port of a dot-server (e.g. localhost:50051); "
        "empty: run one locally")
    tls_ca: StringProperty(
        name="TLS CA", subtype='FILE_PATH', default="",
        description="PEM CA bundle that signed the server's certificate "
        "(enables TLS)")
    tls_cert: StringProperty(
        name="Client Certificate", subtype='FILE_PATH', default="",
        description="PEM client certificate, for servers that require one "
        "(mutual TLS)")
    tls_key: StringProperty(
        name="Client Key", subtype='FILE_PATH', default="",
        description="PEM private key of the client certificate")
    run_locally: BoolProperty(
        name="Run Locally", default=True,
        description="When no server is set, start dot-server on a loopback "
        "port for this Blender session")
    server_executable: StringProperty(
        name="dot-server", subtype='FILE_PATH', default="dot-server",
        description="The dot-server program Run Locally starts (a name on "
        "PATH, or a path; dot-server: $DOT_SERVER_PATH when set, else "
        "dot-server on PATH)")
    timeout: FloatProperty(
        name="Timeout", default=300.0, min=1.0, subtype='TIME', unit='TIME',
        description="Seconds a call may take before it is cancelled")

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "server_address")
        col = layout.column()
        col.enabled = bool(self.server_address.strip())
        col.prop(self, "tls_ca")
        col.prop(self, "tls_cert")
        col.prop(self, "tls_key")
        row = layout.row()
        row.enabled = not self.server_address.strip()
        row.prop(self, "run_locally")
        row.prop(self, "server_executable", text="")
        layout.prop(self, "timeout")
        if connection.local_server_running():
            layout.label(text="A local dot-server is running for this "
                         "session.", icon='INFO')
