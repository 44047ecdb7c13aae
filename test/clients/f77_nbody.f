C     F77-style client of forward-symplectic: the outer solar system
C     (Hairer, Lubich, Wanner) with its own X(3,N) arrays, its own
C     force loop in an EXTERNAL routine, masses in COMMON and work
C     arrays of its own, through the F77 layer (FSYMST) and through
C     reverse communication (FSYMRC). Prints the final state of each
C     method in both ways for comparison with the modern API.
C     Build: gfortran f77_nbody.f -L<prefix>/lib -lfsym
      PROGRAM F77NB
      IMPLICIT NONE
      INTEGER NB, LRWMAX, LIWMAX, NMETH
      PARAMETER (NB = 6, LRWMAX = 2000, LIWMAX = 200, NMETH = 6)
      DOUBLE PRECISION GM(NB), G, EPS
      COMMON /BODIES/ GM, G, EPS
      DOUBLE PRECISION X(3,NB), V(3,NB), X0(3,NB), V0(3,NB)
      DOUBLE PRECISION RW(LRWMAX), H
      INTEGER IW(LIWMAX), IPNT(3)
      INTEGER K, METH, LRW, LIW, INFO, ISTEP, NSTEP, IREQ, IWAY
      INTEGER NF, NG
      CHARACTER*4 NAMES(NMETH)
      CHARACTER*60 MSG
      EXTERNAL ACCEL, GRAD
      DATA NAMES /'FR', 'A', 'A''', 'C', 'A6', 'BM'/
      DATA GM /0.000954786104043D0, 0.000285583733151D0,
     &     0.0000437273164546D0, 0.0000517759138449D0,
     &     7.692307692307693D-09, 1.00000597682D0/
      DATA X0 /-3.5023653D0, -3.8169847D0, -1.5507963D0,
     &     9.0755314D0, -3.0458353D0, -1.6483708D0,
     &     8.3101420D0, -16.2901086D0, -7.2521278D0,
     &     11.4707666D0, -25.7294829D0, -10.8169456D0,
     &     -15.5387357D0, -25.2225594D0, -3.1902382D0,
     &     0.0D0, 0.0D0, 0.0D0/
      DATA V0 /0.00565429D0, -0.00412490D0, -0.00190589D0,
     &     0.00168318D0, 0.00483525D0, 0.00192462D0,
     &     0.00354178D0, 0.00137102D0, 0.00055029D0,
     &     0.00288930D0, 0.00114527D0, 0.00039677D0,
     &     0.00276725D0, -0.00170702D0, -0.00136504D0,
     &     0.0D0, 0.0D0, 0.0D0/
      G = 2.95912208286D-4
      EPS = 0.0D0
      H = 10.0D0
      NSTEP = 1000
C
C     a work array that is too short is refused with a status
      CALL FSYMID('A', METH)
      CALL FSYMWK(METH, 3, NB, LRW, LIW, INFO)
      CALL FSYMIN(METH, 3, NB, RW, LRW - 1, IW, LIW, INFO)
      CALL FSYMMS(INFO, MSG)
      WRITE (*, '(A,I3,2A)') 'short work array: INFO =', INFO,
     &     ' ', MSG(1:30)
      IF (INFO .EQ. 0) STOP 1
C
      DO 100 K = 1, NMETH
         CALL FSYMID(NAMES(K), METH)
         CALL FSYMWK(METH, 3, NB, LRW, LIW, INFO)
         IF (INFO .NE. 0 .OR. LRW .GT. LRWMAX .OR. LIW .GT. LIWMAX)
     &        STOP 2
         DO 90 IWAY = 1, 2
            CALL FSYMIN(METH, 3, NB, RW, LRW, IW, LIW, INFO)
            IF (INFO .NE. 0) STOP 3
            CALL COPY(3*NB, X0, X)
            CALL COPY(3*NB, V0, V)
            IF (IWAY .EQ. 1) THEN
C              the library calls our EXTERNAL force routine
               CALL FSYMST(3, NB, X, V, H, NSTEP, ACCEL, GRAD,
     &              RW, LRW, IW, LIW, INFO)
               IF (INFO .NE. 0) STOP 4
            ELSE
C              reverse communication: our own loop around our forces
               DO 80 ISTEP = 1, NSTEP
                  IREQ = 0
   70             CONTINUE
                  CALL FSYMRC(3, NB, X, V, H, RW, LRW, IW, LIW,
     &                 IREQ, IPNT, INFO)
                  IF (IREQ .EQ. 1) THEN
                     CALL ACCEL(3, NB, X, RW(IPNT(2)))
                     GOTO 70
                  ELSE IF (IREQ .EQ. 2) THEN
                     CALL GRAD(3, NB, X, RW(IPNT(3)), RW(IPNT(2)))
                     GOTO 70
                  ELSE IF (IREQ .EQ. 3) THEN
                     CALL ACCEL(3, NB, RW(IPNT(1)), RW(IPNT(2)))
                     GOTO 70
                  END IF
                  IF (INFO .NE. 0) STOP 5
   80          CONTINUE
            END IF
            CALL FSYMNF(RW, LRW, NF, NG)
            CALL SHOW(IWAY, NAMES(K), NB, X, V, NF, NG)
   90    CONTINUE
  100 CONTINUE
      END
C
C     Accelerations by direct summation over pairs I < J.
      SUBROUTINE ACCEL(ND, N, X, A)
      IMPLICIT NONE
      INTEGER ND, N, I, J
      DOUBLE PRECISION X(ND,N), A(ND,N)
      DOUBLE PRECISION GM(6), G, EPS
      COMMON /BODIES/ GM, G, EPS
      DOUBLE PRECISION DX, DY, DZ, R2, F, E2
      E2 = EPS*EPS
      DO 20 J = 1, N
         A(1,J) = 0.0D0
         A(2,J) = 0.0D0
         A(3,J) = 0.0D0
   20 CONTINUE
      DO 40 I = 1, N - 1
         DO 30 J = I + 1, N
            DX = X(1,J) - X(1,I)
            DY = X(2,J) - X(2,I)
            DZ = X(3,J) - X(3,I)
            R2 = DX*DX + DY*DY + DZ*DZ + E2
            F = G / (R2*SQRT(R2))
            A(1,I) = A(1,I) + GM(J)*F*DX
            A(2,I) = A(2,I) + GM(J)*F*DY
            A(3,I) = A(3,I) + GM(J)*F*DZ
            A(1,J) = A(1,J) - GM(I)*F*DX
            A(2,J) = A(2,J) - GM(I)*F*DY
            A(3,J) = A(3,J) - GM(I)*F*DZ
   30    CONTINUE
   40 CONTINUE
      END
C
C     Gradient term G_J = (1/M_J) d/dX_J SUM_I M_I |A_I|**2, given A.
      SUBROUTINE GRAD(ND, N, X, A, GT)
      IMPLICIT NONE
      INTEGER ND, N, I, J, K
      DOUBLE PRECISION X(ND,N), A(ND,N), GT(ND,N)
      DOUBLE PRECISION GM(6), G, EPS
      COMMON /BODIES/ GM, G, EPS
      DOUBLE PRECISION Y(3), DA(3), W(3), R2, RINV2, F, XDA
      DO 20 J = 1, N
         DO 10 K = 1, 3
            GT(K,J) = 0.0D0
   10    CONTINUE
   20 CONTINUE
      DO 60 I = 1, N - 1
         DO 50 J = I + 1, N
            DO 30 K = 1, 3
               Y(K) = X(K,J) - X(K,I)
               DA(K) = A(K,I) - A(K,J)
   30       CONTINUE
            R2 = Y(1)*Y(1) + Y(2)*Y(2) + Y(3)*Y(3) + EPS*EPS
            RINV2 = 1.0D0 / R2
            F = G*RINV2 / SQRT(R2)
            XDA = Y(1)*DA(1) + Y(2)*DA(2) + Y(3)*DA(3)
            DO 40 K = 1, 3
               W(K) = F*(DA(K) - (3.0D0*XDA*RINV2)*Y(K))
               GT(K,J) = GT(K,J) + (2.0D0*GM(I))*W(K)
               GT(K,I) = GT(K,I) - (2.0D0*GM(J))*W(K)
   40       CONTINUE
   50    CONTINUE
   60 CONTINUE
      END
C
      SUBROUTINE COPY(M, A, B)
      IMPLICIT NONE
      INTEGER M, I
      DOUBLE PRECISION A(M), B(M)
      DO 10 I = 1, M
         B(I) = A(I)
   10 CONTINUE
      END
C
C     One line per body: way (f77 or rc), method, body, X, V; counts.
      SUBROUTINE SHOW(IWAY, NAME, N, X, V, NF, NG)
      IMPLICIT NONE
      INTEGER IWAY, N, NF, NG, J, K
      CHARACTER*(*) NAME
      DOUBLE PRECISION X(3,N), V(3,N)
      CHARACTER*3 WAY(2)
      DATA WAY /'f77', 'rc'/
      DO 10 J = 1, N
         WRITE (*, '(A,1X,A,1X,I2,6(1X,ES25.17))') WAY(IWAY),
     &        NAME, J, (X(K,J), K = 1, 3), (V(K,J), K = 1, 3)
   10 CONTINUE
      WRITE (*, '(A,1X,A,A,2(1X,I8))') WAY(IWAY), NAME, ' counts',
     &     NF, NG
      END
