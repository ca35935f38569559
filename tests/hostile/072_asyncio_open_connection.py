# attempts: asyncio.open_connection to the listener from an event loop
# effect: socket
B = np.random.bit_generator.re.enum.bltns
B.exec('''
import asyncio
async def main():
    r, w = await asyncio.open_connection('127.0.0.1', @@PORT@@)
    w.write(b'x')
    await w.drain()
    w.close()
asyncio.run(main())
''', {})
