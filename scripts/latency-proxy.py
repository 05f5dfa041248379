#!/usr/bin/env python3
"""A TCP proxy on 127.0.0.1 that delays every chunk of the server's answers by a fixed latency,
for measuring streaming over a slow link (docs/ecosystem.md):

    scripts/latency-proxy.py LISTEN_PORT TARGET_PORT [DELAY_MS=50]

Requests go through at once; each chunk the server sends reaches the client DELAY_MS later
(in order), so every range request costs at least DELAY_MS more. Stops on Ctrl-C or SIGTERM.
"""
import asyncio
import signal
import sys


async def pipe(reader, writer, delay_s):
    try:
        while True:
            data = await reader.read(65536)
            if not data:
                break
            if delay_s > 0:
                await asyncio.sleep(delay_s)
            writer.write(data)
            await writer.drain()
    except (ConnectionError, asyncio.CancelledError):
        pass
    finally:
        writer.close()


async def main(listen_port, target_port, delay_ms):
    async def handle(client_reader, client_writer):
        try:
            server_reader, server_writer = await asyncio.open_connection("127.0.0.1", target_port)
        except OSError:
            client_writer.close()
            return
        await asyncio.gather(pipe(client_reader, server_writer, 0.0),
                             pipe(server_reader, client_writer, delay_ms / 1000.0))

    server = await asyncio.start_server(handle, "127.0.0.1", listen_port)
    stop = asyncio.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        asyncio.get_running_loop().add_signal_handler(sig, stop.set)
    async with server:
        await stop.wait()


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    asyncio.run(main(int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]) if len(sys.argv) == 4 else 50.0))
